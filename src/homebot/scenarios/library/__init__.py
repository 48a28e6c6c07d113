"""The seeds' demonstrations, run by ``homebot scenario NAME``.

Each module here is one scenario. It exposes ``add_arguments(parser)`` (besides
``--seed`` and ``--json``, which every scenario gets) and
``run(args, console) -> dict``, returning the summary every scenario prints:
``{"scenario", "success", "actions": [...], "speech": [...]}`` plus figures of its
own (build it with ``homebot.scenarios.summary.scenario_summary``). ``console``
is None under ``--json``: then the scenario prints nothing.
"""
