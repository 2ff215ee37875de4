"""Caregiver (thesis §3.5, Tables 3.1–3.3, Figures 3.14–3.16): a robot that keeps a novice safe.

Five novice types (ε-greedy toward toy bins, ε from 1 to 0.05) play 200-step episodes in the ``house`` map,
with and without the caregiver (:mod:`supportive.safety`); one trial = one episode of every type without
and, from the same seed, with the caregiver under each reading of P(safe | τ) (:mod:`.measure`). Reported: mean normalised damage, steps until the critical
damage of 15, cells explored until then, each with its standard deviation (:mod:`.report`, :mod:`.plots`).

>>> from supportive.experiments import get
>>> get("caregiver").default_trials
100
"""

from supportive.experiments.caregiver import measure, plots, report
from supportive.experiments.registry import declare

__all__ = ["CAREGIVER"]

CAREGIVER = declare(
    name="caregiver",
    title="Caregiver: keeping a novice safe while it explores",
    reference="§3.5, Tables 3.1–3.3, Figures 3.14–3.16",
    parts=(measure, plots, report),
)
"""The registered experiment."""
