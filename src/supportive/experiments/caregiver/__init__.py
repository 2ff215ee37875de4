"""Caregiver (thesis §3.5, Tables 3.1–3.3, Figures 3.14–3.16): a robot that keeps a novice safe.

Five novice types (ε-greedy toward toy bins, ε from 1 to 0.05) play 200-step episodes in the ``house`` map,
with and without the caregiver (:mod:`supportive.safety`); one trial = one episode of every type without
and, from the same seed, with the caregiver under each reading of P(safe | τ) (:mod:`.measure`). Reported: mean normalised damage, steps until the critical
damage of 15, cells explored until then, each with its standard deviation (:mod:`.report`, :mod:`.plots`).

>>> from supportive.experiments import get
>>> get("caregiver").default_trials
100
"""

from supportive.experiments.caregiver.measure import (
    CONDITIONS,
    DEFAULT_EPISODES,
    MAP,
    MEMORIES,
    READINGS,
    make_trials,
    run_trial,
)
from supportive.experiments.caregiver.plots import FILES, plots
from supportive.experiments.caregiver.report import (
    MEASURES,
    THESIS,
    findings,
    headline,
    report,
    summarize,
    verdict,
)
from supportive.experiments.registry import Experiment, register

__all__ = [
    "CAREGIVER",
    "CONDITIONS",
    "DEFAULT_EPISODES",
    "FILES",
    "MAP",
    "MEASURES",
    "MEMORIES",
    "READINGS",
    "THESIS",
    "findings",
    "headline",
    "make_trials",
    "plots",
    "report",
    "run_trial",
    "summarize",
    "verdict",
]

CAREGIVER = register(
    Experiment(
        name="caregiver",
        title="Caregiver: keeping a novice safe while it explores",
        reference="§3.5, Tables 3.1–3.3, Figures 3.14–3.16",
        thesis=THESIS,
        default_trials=DEFAULT_EPISODES,
        make_trials=make_trials,
        run_trial=run_trial,
        summarize=summarize,
        report=report,
        plots=plots,
        headline=headline,
        readings=READINGS,
        findings=findings,
    )
)
"""The registered experiment."""
