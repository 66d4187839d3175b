"""One module per kind of section of a worked solution; each builder reads a
:class:`tutgen.render.blocks.SolutionContext` and returns its section (or ``None`` when the derivation
has nothing to show). :data:`tutgen.render.views.BUILDERS` maps the kinds of step to them."""
