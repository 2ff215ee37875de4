"""Files in and out: task files (YAML/JSON/CSV), learned HTNs (JSON, DOT, HDDL, text tree), datasets."""

from supportive.io.observation_file import parse_observation_file
from supportive.io.taskfile import (
    dump_task,
    format_of,
    parse_task_file,
    parse_task_string,
    task_to_dict,
    write_task_file,
)

__all__ = [
    "dump_task",
    "format_of",
    "parse_observation_file",
    "parse_task_file",
    "parse_task_string",
    "task_to_dict",
    "write_task_file",
]
