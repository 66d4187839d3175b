"""Jinja templates of the worked solutions (installed as the package data `tutgen.templates`)."""
