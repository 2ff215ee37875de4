"""``supportive support``: what a support robot would do at a circuit table, and a simulated comparison."""

from __future__ import annotations

import json
import sys
from enum import StrEnum
from pathlib import Path
from typing import Annotated

import typer

from supportive.cli.interrupt import writing
from supportive.cli.output import about, local_workers, say
from supportive.extras import require_extra

__all__ = ["support"]


class SupportLead(StrEnum):
    """Leads ``support --simulate`` can run."""

    plans = "plans"
    greedy = "greedy"


def support(
    file: Annotated[
        Path, typer.Argument(help="Circuit scenario file (.yaml, .yml or .json), or a bundled one's name.")
    ],
    seed: Annotated[
        int, typer.Option("--seed", min=0, help="Seeds the sampling (same seed, same choice).")
    ] = 0,
    environments: Annotated[
        int | None,
        typer.Option("--environments", "-e", min=1, max=100_000, help="Hypothetical environments to sample."),
    ] = None,
    scheme: Annotated[
        str | None, typer.Option("--scheme", metavar="conservative|greedy|aggressive", help="Plan weights: conservative, greedy or aggressive.")
    ] = None,
    workers: Annotated[
        int, typer.Option("--workers", "-w", min=1, max=256, help="Local processes scoring them.")
    ] = 1,
    render: Annotated[
        Path | None,
        typer.Option("--render", help="Draw the table before and after as a PNG (needs matplotlib)."),
    ] = None,
    simulate: Annotated[
        bool, typer.Option("--simulate", help="Also run the lead alone and with the support agent.")
    ] = False,
    lead: Annotated[
        SupportLead, typer.Option("--lead", help="The lead --simulate runs.")
    ] = SupportLead.plans,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON instead of sentences.")] = False,
) -> None:
    """Show what a support robot would do at a circuit table (§3.2): the supportive action it chooses, the
    known plans it favours and the lead's expected saving."""
    from dataclasses import replace

    from supportive.envs.circuits.advice import advise
    from supportive.envs.circuits.advice import simulate as run_simulation
    from supportive.envs.circuits.scenario import parse_scenario_file
    from supportive.examples import scenario_path
    from supportive.planning.weighting import parse_scheme
    from supportive.render.circuits import write_before_after
    from supportive.render.files import picture_path

    local_workers(workers)
    if render is not None:
        require_extra("drawing the circuit table (--render)", "matplotlib", "plot")
        picture_path(render, ".png", "the picture")  # before planning: a folder or a name without .png is refused
    file = scenario_path(file)
    scenario = parse_scenario_file(file)
    if environments is not None:
        scenario = replace(scenario, environments=environments)
    if scheme is not None:
        scenario = replace(scenario, scheme=parse_scheme(scheme))
    with about(file):
        plans = scenario.plans()
        advice, decision = advise(scenario, plans, seed=seed, workers=workers)
    report: dict[str, object] = advice.as_dict()
    simulation = None
    if simulate:
        with about(file):
            simulation = run_simulation(scenario, plans, lead.value, seed=seed, workers=workers)
        report["simulation"] = simulation.as_dict()
    if as_json:
        sys.stdout.write(json.dumps(report, indent=2) + "\n")
    else:
        for line in advice.lines():
            say(line)
        if simulation is not None:
            say(simulation.line())
    if render is not None:
        world = scenario.world
        after = decision.chosen.state
        with writing(render):
            write_before_after(world, world.initial_state, after, render, moved=decision.chosen.move)
        say(f"wrote {render}", to_stderr=True)
