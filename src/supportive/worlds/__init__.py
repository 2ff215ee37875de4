"""World models the algorithm layers reason over directly: the household of the caregiver (§3.5).

A world the planner reaches only through a protocol it owns (:class:`~supportive.planning.world.SupportWorld`)
lives in :mod:`supportive.envs` beside its Gymnasium/PettingZoo adapters; a world an algorithm layer needs
concretely (the caregiver's maps, moves and damage) lives here, below that layer.
"""
