"""Tutorial sheets: several problem specs as one question sheet and one solution sheet, and randomised
variants of them, one per student, each with its concrete specs and answer keys (docs/sheets.md).

The flow is the pipeline's, once per problem and then once per variant::

    sheet.yaml ─load─▶ Sheet (problems: base System each) ─derive once─▶ Derivation per problem
        ─sample (seed, problem, variant)─▶ values ─substitute─▶ Derivation per variant ─render─▶ files

- :mod:`tutgen.sheet.model`: the sheet file and the roster, read with located errors;
- :mod:`tutgen.sheet.variants`: deterministic sampling, the concrete spec text of a variant;
- :mod:`tutgen.sheet.render`: the question and solution sheets and the answer keys;
- :mod:`tutgen.sheet.executor`: where the variants are built (in-process, a process pool, Dask);
- :mod:`tutgen.sheet.build`: the whole build, gathered before anything is written.
"""
