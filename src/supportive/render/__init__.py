"""Drawing what the library returns, above every library layer and below the command layer: text for a
terminal (rich) and pictures (matplotlib, the ``plot`` extra, imported only when one is drawn).

* :mod:`~supportive.render.terminal` — the one escaping rule for a user's text on a terminal, and the console;
* :mod:`~supportive.render.tables` — tables that fit the terminal without cutting a word or a number;
* :mod:`~supportive.render.tree` — a learned HTN as a tree;
* :mod:`~supportive.render.household` — caregiver episodes as text, rich panels and animated GIFs;
* :mod:`~supportive.render.circuits` — the circuit table before and after a supportive action, as a PNG.

The library's own exports (JSON, DOT, HDDL, task files) are data and live in :mod:`supportive.io`; the
experiments' report plots live with each experiment (:mod:`supportive.experiments`).
"""
