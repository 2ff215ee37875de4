"""Supportive behaviors a person can ask for and a robot can explain (§3.1, §3.3)."""
