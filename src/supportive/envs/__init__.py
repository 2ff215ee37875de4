"""Simulated worlds: the household of the caregiver experiment (§3.5)."""
