"""The spec -> model step, one builder module per section of a spec, sharing one context.

:func:`tutgen.spec.builders.system.build_system` calls the builders in order; each one reads its part of
the :class:`~tutgen.spec.schema.SpecDoc` through the :class:`~tutgen.spec.builders.context.Context`,
which holds the names declared so far and collects every problem with its ``file:line:col``.
"""
