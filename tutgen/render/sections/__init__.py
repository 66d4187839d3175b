"""One module per kind of section of a worked solution; each builder reads a
:class:`tutgen.render.blocks.SolutionContext` and returns its section (or ``None`` when the spec did not
ask for it or the derivation has nothing to show). :data:`tutgen.render.views.SECTIONS` orders them."""
