"""The limits on what `supportive` reads from users, in one place (docs/limits.md explains each).

Each is far above the largest input the benchmarks and bundled examples use (a 5,000-action task file of
0.8 MB, 37 levels deep), and low enough that a hostile or broken input is refused in well under a second
with one clear line instead of a hang, a traceback or gigabytes of memory.
"""

from __future__ import annotations

__all__ = [
    "MAX_CSV_FIELD",
    "MAX_DEPTH",
    "MAX_FILE_BYTES",
    "MAX_GENERATED_STEPS",
    "MAX_ID_LENGTH",
    "MAX_MAP_CELLS",
    "MAX_MAP_SIDE",
    "MAX_NODES",
    "MAX_NUMBER_CHARS",
    "MAX_SECONDS",
    "MAX_SENTENCE_CHARS",
]

MAX_FILE_BYTES = 16 * 1024 * 1024
"""The largest file read (task files, observation streams, scenarios, maps): 16 MiB."""

MAX_GENERATED_STEPS = 300_000
"""The most steps ``supportive generate`` draws (actions × demonstrations), checked before it starts: some
7 MB of YAML and, with 100,000 actions, 40 s on two cores. The file it writes must also stay within
:data:`MAX_FILE_BYTES`, so that it can be read back (checked before it is written)."""

MAX_DEPTH = 100
"""The deepest nesting of lists and mappings in a YAML or JSON file."""

MAX_NODES = 2_000_000
"""The most values (scalars, lists, mappings) a YAML or JSON document may hold, an alias counting as all the
values it repeats: a small file of aliases of aliases ("billion laughs") cannot expand past it."""

MAX_NUMBER_CHARS = 100
"""The longest number written in a file (digits, sign, point and exponent)."""

MAX_CSV_FIELD = 131_072
"""The longest CSV field, characters (Python's csv default)."""

MAX_ID_LENGTH = 200
"""The longest id (action, demonstration, agent, subtask name), characters."""

MAX_SECONDS = 1e11
"""The largest time (a step's start or end, an observation's or a hand sample's ``t``), seconds: 3,000 years,
so Unix timestamps (1.7e9 s) pass and the squares the social force computes stay finite."""

MAX_SENTENCE_CHARS = 500
"""The longest sentence ``chat`` (and :func:`~supportive.language.grammar.parse_utterance`) reads."""

MAX_MAP_SIDE = 120
"""The most rows or columns of a household map."""

MAX_MAP_CELLS = 2_500
"""The most cells of a household map's play area (floor cells the novice and the caregiver can reach)."""
