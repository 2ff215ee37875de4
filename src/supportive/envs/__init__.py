"""Simulated worlds with Gymnasium / PettingZoo APIs and the worlds the support planner acts in: the
household's RL environments (§3.5), the circuit table (§3.2), the tabletop team and the chair workshop."""
