"""``robodesc batch``: many robots in one run, on every core or on a Ray cluster.

The driver (:mod:`.runner`) turns inputs into :class:`~.jobs.Job` objects (files, folders searched
by :mod:`.discover`, manifests read by :mod:`.manifest`, xacro-argument sweeps expanded by
:mod:`.sweep`), skips the jobs whose recorded inputs, options and robodesc build are unchanged
(:mod:`.cache`), runs the rest through one per-job function (:func:`.worker.run_job`) in a local
process pool or as Ray tasks (:mod:`.executors`), and writes the summary (:mod:`.summary`).

Only :mod:`robodesc.cli` imports this package; it imports the pipeline, like the CLI does.

The Python entry points are :func:`robodesc.batch.plan.plan` and :func:`robodesc.batch.runner.run_batch`
(not re-exported here: the CLI imports this package's command module on every start, so the package
itself imports nothing).
"""
