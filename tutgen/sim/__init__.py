"""`tutgen simulate`: forward dynamics integrated, the trajectory written and plotted (docs/simulate.md).

scipy and matplotlib (the `sim` extra) are imported only inside the functions that need them.
"""
