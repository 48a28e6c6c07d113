"""The seeds' demonstrations, run by ``homebot scenario NAME``.

Each module here is one scenario. It exposes ``SHARED_OPTIONS`` (the options whose
checks belong to the command line, ``homebot.scenarios.running.SharedOption``; none when
absent), ``add_arguments(parser)`` (its own plain options, besides ``--seed`` and
``--json``, which every scenario gets) and ``run(args, console, build) -> dict``, where
``build`` is the caller's ``RunBuilder`` (the scenario builds no run itself), returning
the summary every scenario prints:
``{"scenario", "success", "actions": [...], "speech": [...]}`` plus figures of its
own (build it with ``homebot.scenarios.summary.scenario_summary``). ``console``
is None under ``--json``: then the scenario prints nothing.
"""
