"""Figures: a schematic of every mechanism, drawn from its model.

``build.draw_system(system)`` makes one :class:`~tutgen.figure.scene.Drawing` (primitives in picture
centimetres, labels with their TeX text and bounding boxes); ``tikz.to_tikz`` and ``svg.to_svg`` are
its two back ends. Nothing here derives dynamics: the drawing reads the model only.
"""
