"""The household's RL environments (the ``envs`` extra: gymnasium, pettingzoo):
:class:`~supportive.envs.household.gym_env.NoviceEnv` (registered as ``supportive/Household-v0``) and
:class:`~supportive.envs.household.parallel_env.HouseholdParallelEnv`; import them from those modules. The world
they wrap (maps, dynamics, novices) is :mod:`supportive.worlds.household`."""
