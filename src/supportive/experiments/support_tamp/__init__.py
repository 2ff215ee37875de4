"""Supportive-behavior TAMP (thesis §3.2.9, Figures 3.5–3.6): a support robot rearranges a circuit-building
table for a lead it cannot talk to.

One trial = one random table of the thesis-size task, run for both scenarios (an unpredictable lead that
knows a random subset of Π_T, with conservative weights; a greedy heuristic lead, with aggressive weights)
and every pairing of fast (100 %) and slow (33 %) lead and support agent, with and without support
(:mod:`.measure`), the support agent minimising the expected duration of the lead's plans (reading
``duration``, the default) or that plus the greedy lead's search (``search-aware``). Reported: makespan and
its gain as a reduction and as a speed-up, the motion model's ceiling, the lead's search nodes and planning
time, support actions and conflicts (:mod:`.report`, :mod:`.plots`).

>>> from supportive.experiments import get
>>> get("support-tamp").reference
'§3.2.9, Figures 3.5–3.6'
"""

from supportive.experiments.registry import declare
from supportive.experiments.support_tamp import measure, plots, report

__all__ = ["SUPPORT_TAMP"]

SUPPORT_TAMP = declare(
    name="support-tamp",
    title="Supportive-behavior TAMP: a support robot rearranges a circuit-building table",
    reference="§3.2.9, Figures 3.5–3.6",
    parts=(measure, plots, report),
)
"""The registered experiment."""
