"""Files in and out: task files (YAML/JSON/CSV), learned HTNs (JSON, DOT, HDDL), observation streams, ROS
bags, datasets; safe reading of hostile files and atomic, comment-keeping saves."""

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
