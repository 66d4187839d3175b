"""The mass properties of each body, as a teacher works them: each part's moments from its shape's formula
(symbols, then numbers with units), each parallel-axis shift with its m d^2 term, the sum over the parts,
the products of inertia, the centre of mass, the tensor about it, and the principal moments and axes about
the body frame's origin O and about the centre of mass G, each labelled with its point."""

from __future__ import annotations

import re
from typing import Any

import sympy as sp

from tutgen.engine.inertia import AXES, ENTRIES, BodyInertia, PartInertia, Principal, ShapeFormula
from tutgen.engine.steps import StepKind
from tutgen.model.system import Shape
from tutgen.render.blocks import (
    Block,
    SolutionContext,
    as_number,
    boxed,
    chain,
    display,
    math,
    para,
    prose,
    section,
    stacked,
    subheading,
    text,
    unit_tex,
)
from tutgen.render.layout import LINE_WIDTH_PT, tex_width

MASS, LENGTH, VOLUME, INERTIA = "kg", "m", "m^3", "kg*m^2"
#: the widest matrix m(|r_G|^2 E - r_G r_G^T) printed in the shift to the centre of mass
SHIFT_WIDTH = 0.5 * LINE_WIDTH_PT

#: what the symbols of a shape's formula stand for, as the solution says it
_SYMBOL_WORDS = {
    Shape.BOX: "its edges along its own x, y, z axes",
    Shape.CYLINDER: "its radius and length",
    Shape.HOLLOW_CYLINDER: "its outer and inner radii and length",
    Shape.THIN_CYLINDER: "its radius and length",
    Shape.ROD: "its length",
    Shape.DISC: "its radius",
    Shape.SPHERE: "its radius",
    Shape.SPHERICAL_SHELL: "its radius",
}


def mass_properties(c: SolutionContext) -> dict[str, Any] | None:
    d, s = c.d, c.s
    if not d.has_step(StepKind.INERTIA) or not d.inertia:
        return None
    sec = section(
        "Mass properties",
        "$J_{ab} = \\int (r^2\\delta_{ab} - a\\,b)\\,dm$: the diagonal holds the moments of inertia, the "
        "off-diagonal entries are minus the products of inertia $P_{ab} = \\int a\\,b\\,dm$. Each part's "
        "inertia about its own centroid $G_p$ comes from its shape's formula; the parallel-axis theorem moves it "
        "to the body frame's origin $O$ entry by entry, $J_{O,aa} = J_{G,aa} + m\\,d^2$ ($d$ the distance "
        "between the two parallel axes) and $J_{O,ab} = J_{G,ab} - m\\,d_a d_b$.",
    )
    blocks = sec["blocks"]
    for bi, principal in zip(d.inertia, d.principal, strict=True):
        if s.coordinates and all(p.shape is Shape.POINT for p in bi.parts) and len(bi.parts) <= 1:
            continue  # a lone point mass: its inertia is m r^2 in the energies, nothing to tabulate
        tables = _part_tables(c, bi)
        if tables is None:
            for p in bi.parts:
                blocks += _part_blocks(c, bi, p)
        else:
            blocks += tables
        blocks += _body_blocks(c, bi, summed=tables is not None)
        for point, found in (("O", principal.origin), ("G", principal.com)):
            if found is not None:
                blocks += _principal_blocks(c, point, found)
    return sec if blocks else None


def _value(c: SolutionContext, expr: Any, unit: str) -> str:
    """A result as printed: a number with its SI unit, a formula (symbols left) as it is."""
    v = as_number(c.num(expr))
    printed = c.tex(v)
    has_symbols = bool(v.free_symbols) if isinstance(v, sp.Basic | sp.MatrixBase) else False
    zero = v == 0 if isinstance(v, sp.Basic) else all(e == 0 for e in v)
    return printed + (unit_tex(unit) if not has_symbols and not zero else "")


def _moment_line(c: SolutionContext, f: ShapeFormula, label: str, formula: sp.Expr) -> str:
    """``J_{G,xx} = 1/12 m (b^2 + c^2) = 1/12 . 2.943 . (0.15^2 + 0.05^2) = 0.006132 kg m^2`` (a rod's axial
    moment: ``J_{G,xx} = 0``)."""
    value = _value(c, formula.subs(dict(f.symbols)), INERTIA)
    if formula == 0:
        return f"{_entry('G', label)} = {value}"
    numbers = {sym: as_number(c.num(v)) for sym, v in f.symbols}
    forms = [shape_tex(f, formula)]
    if all(not n.free_symbols for n in numbers.values()):  # the formula with the part's numbers put in
        forms.append(shape_tex(f, formula, {sym: c.tex(n) for sym, n in numbers.items()}))
    return f"{_entry('G', label)} = " + " = ".join([*forms, value])


def shape_tex(
    f: ShapeFormula, formula: sp.Expr, numbers: dict[sp.Symbol, str] | None = None, *, stacked: bool = False
) -> str:
    r"""A shape's moment as a textbook writes it: the fraction first, then the mass, then the shape's sizes
    in the order the shape names them (``\tfrac{1}{12} m (3 r^2 + h^2)``, not sympy's ``m (h^2 + 3 r^2)/12``
    nor ``l^2 m/12``); with ``numbers`` (each symbol's printed value), the same with the numbers put in,
    factors joined by ``\cdot`` (``\tfrac{1}{12} \cdot 15 \cdot 1.5^{2}``). A formula not of the form
    (fraction) (mass) (product or sum of products of the sizes) is printed by sympy, as it is. ``stacked``
    sets the fraction over the whole (``\frac{m (3 r^2 + h^2)}{12}``): narrower, for a table's cell."""

    def as_sympy() -> str:
        """The formula as sympy prints it (with the numbers put in, if given)."""
        if numbers is None:
            return sp.latex(formula)
        return sp.latex(formula, symbol_names=numbers, mul_symbol="dot")

    order = {sym: i for i, (sym, _) in enumerate(f.symbols)}
    coeff, rest = formula.as_coeff_Mul()
    factors = list(sp.Mul.make_args(rest))
    masses = [x for x in factors if x in order and order[x] == 0]
    factors = [x for x in factors if x not in masses]
    if not coeff.is_Rational or coeff <= 0 or len(masses) != 1 or len(factors) > 1:
        return as_sympy()
    dot = " \\cdot " if numbers is not None else " "

    def name(sym: sp.Basic) -> str:
        return numbers[sym] if numbers is not None else sp.latex(sym)

    def product(term: sp.Expr) -> str | None:
        """``3 r^{2}``: an integer, then the sizes in the shape's order, each to its power."""
        k, monomial = term.as_coeff_Mul()
        powers = [b.as_base_exp() for b in sp.Mul.make_args(monomial)]
        if not (k.is_Integer and k > 0) or any(b not in order or not e.is_Integer or e < 1 for b, e in powers):
            return None
        shown = [str(k)] if k != 1 else []
        for b, e in sorted(powers, key=lambda be: order[be[0]]):
            printed = name(b) if numbers is None else _paren(name(b))
            shown.append(printed if e == 1 else f"{printed}^{{{e}}}")
        return dot.join(shown)

    def first(term: sp.Expr) -> int:
        return min((order.get(x, len(order)) for x in term.free_symbols), default=len(order))

    body = factors[0] if factors else sp.S.One
    if body.is_Add:
        terms = [product(t) for t in sorted(sp.Add.make_args(body), key=first)]
        printed = None if None in terms else f"\\left({' + '.join(t for t in terms if t)}\\right)"
    else:
        printed = product(body) if factors else ""
    if printed is None:
        return as_sympy()
    mass = name(masses[0]) if numbers is None else _paren(name(masses[0]))
    if stacked and coeff.q != 1:
        above = dot.join(x for x in (str(coeff.p) if coeff.p != 1 else "", mass, printed) if x)
        return f"\\frac{{{above}}}{{{coeff.q}}}"
    lead = "" if coeff == 1 else f"\\tfrac{{{coeff.p}}}{{{coeff.q}}}" if coeff.q != 1 else str(coeff.p)
    return dot.join(x for x in (lead, mass, printed) if x)


def _chain(c: SolutionContext, name: str, expr: sp.Expr, unit: str) -> str:
    """``V = 3/8000 = 375e-6 m^3``: the formula, then the number with its unit; a form that prints the same
    as the one before it (``m = 1 = 1 kg``, ``m = m``) is left out."""
    formula, number = c.tex(expr), c.tex(as_number(c.num(expr)))
    forms = [formula] if formula != number else []
    return chain(name, *forms, _value(c, expr, unit))


def _part_label(p: PartInertia) -> str:
    """A part by its name and, unless its name says it already, its shape: ``block (box)``, ``cylinder``
    (not ``cylinder (cylinder)``), ``hub (hollow cylinder)``."""
    shape = p.shape.value.replace("_", " ")
    return p.name if p.name.replace("_", " ").strip().casefold() == shape else f"{p.name} ({shape})"


def _entry(point: str, label: str) -> str:
    """``J_{G,xx}``; a label of equal entries ``yy = zz`` as ``J_{G,yy} = J_{G,zz}``."""
    if label in ("axial", "transverse"):
        return f"J_{{{point},\\mathrm{{{label}}}}}"
    return " = ".join(f"J_{{{point},{part.strip()}}}" for part in label.split("="))


def _part_blocks(c: SolutionContext, bi: BodyInertia, p: PartInertia) -> list[Block]:
    tex, num = c.tex, c.num
    out: list[Block] = [subheading(f"{bi.name} / {_part_label(p)}")]
    chains = [_chain(c, "m", p.mass, MASS)]
    if p.volume is not None:
        chains.insert(0, _chain(c, "V", p.volume, VOLUME))
    out += [display(ch) for ch in chains if ch]
    f = p.formula
    if f is not None:
        symbols = ",\\ ".join(  # "h = h" (a parameter of the shape's own name) says nothing: left out
            f"{sp.latex(sym)} = {shown}"
            for sym, val in f.symbols
            if (shown := _value(c, val, MASS if str(sym) == "m" else LENGTH)) != sp.latex(sym)
        )
        words = _SYMBOL_WORDS.get(p.shape, "")
        axis = ""
        if f.axis is not None:
            axis = f", its axis along ${tex(as_number(num(f.axis.T)))}$"
        given = [math(symbols), text("; ")] if symbols else []
        out.append(para(text("About its centroid, by its shape's formulas ("), *given, prose(f"{words}{axis}):")))
        out.append(stacked([_moment_line(c, f, label, formula) for label, formula in f.moments]))
        if f.turned:
            out.append(para(text("In the body's axes:")))
            out.append(display(f"J_{{G}} = {_value(c, p.inertia_centroid, INERTIA)}"))
    elif p.shape is Shape.GENERAL:
        out.append(para(text("About its centroid, as given:")))
        out.append(display(f"J_{{G}} = {_value(c, p.inertia_centroid, INERTIA)}"))
    elif p.shape is Shape.POINT:
        out.append(para(text("A point mass has no inertia about its own centroid.")))
    if any(x != 0 for x in p.centroid):
        out.append(
            para(
                text("Its centroid is at "),
                math(f"\\mathbf d = {_value(c, p.centroid.T, LENGTH)}"),
                text(" from O; the parallel-axis theorem, entry by entry:"),
            )
        )
        out.append(stacked([_shift_line(c, p, k) for k in range(len(ENTRIES)) if _shift_shown(p, k)]))
    return out


def _shift_shown(p: PartInertia, k: int) -> bool:
    sh = p.shifts[k]
    return sh.value != 0 or sh.centroidal != 0


def _shift_line(c: SolutionContext, p: PartInertia, k: int) -> str:
    """``J_{O,xx} = J_{G,xx} + m(d_y^2 + d_z^2) = 3.853e-4 + 1.233 (0.05^2) = 3.468e-3 kg m^2``."""
    tex, num = c.tex, c.num
    label, i, j = ENTRIES[k]
    sh = p.shifts[k]
    d = [as_number(num(x)) for x in p.centroid]
    mass = tex(as_number(num(p.mass)))
    if i == j:
        used = [m for m in range(3) if m != i and d[m] != 0]
        symbolic = "m\\,(" + " + ".join(f"d_{AXES[m]}^2" for m in range(3) if m != i) + ")"
        numbers = " + ".join(f"{_paren(tex(d[m]))}^2" for m in used)
        term = (f"{mass} \\cdot ({numbers})" if len(used) > 1 else f"{mass} \\cdot {numbers}") if used else "0"
        sign = " + "
    else:
        symbolic = f"m\\,d_{AXES[i]} d_{AXES[j]}"
        term = f"{mass} \\cdot {_paren(tex(d[i]))} \\cdot {_paren(tex(d[j]))}" if d[i] != 0 and d[j] != 0 else "0"
        sign = " - "
    centroidal = tex(as_number(num(sh.centroidal)))
    return (
        f"J_{{O,{label}}} = J_{{G,{label}}}{sign}{symbolic} = {centroidal}{sign}{term} = {_value(c, sh.value, INERTIA)}"
    )


#: a printed factor that needs no brackets before a power: a plain number or one (indexed) name
_ATOM = re.compile(r"[0-9.]+|\\?[A-Za-z]+(_\{?[A-Za-z0-9]+\}?)?")


def _paren(printed: str) -> str:
    """A printed factor in brackets when it is a sum, negative, a power or in engineering notation
    (``375 \\times 10^{-6}``), so that a square reads right and TeX sees no double superscript."""
    return printed if _ATOM.fullmatch(printed) else f"\\left({printed}\\right)"


def _body_blocks(c: SolutionContext, bi: BodyInertia, summed: bool = False) -> list[Block]:
    """The body's tensor about O (``summed``: its sum over the parts was given with the parts' tables),
    its products of inertia, centre of mass and tensor about the centre of mass."""
    tex, num = c.tex, c.num
    out: list[Block] = []
    several = len(bi.parts) > 1
    if summed:
        out.append(subheading(f"{bi.name}, about O:"))
    elif several:
        out.append(subheading(f"{bi.name}: the sum over its parts, about O"))
        lines, zeros = [], []
        for entry in bi.composite:
            if all(t == 0 for t in entry.terms):
                zeros.append(f"J_{{O,{entry.label}}}")
                continue
            terms = " + ".join(tex(as_number(num(t))) for t in entry.terms).replace("+ -", "- ")
            lines.append(f"J_{{O,{entry.label}}} = {terms} = {_value(c, entry.total, INERTIA)}")
        out.append(stacked(lines))
        if zeros:
            out.append(para(math(" = ".join(zeros) + " = 0"), text(" (zero for every part).")))
    else:
        out.append(subheading(f"{bi.name}, about O:"))
    total = [chain("m", _value(c, bi.mass, MASS)), f"J_O = {_value(c, bi.inertia_origin, INERTIA)}"]
    out.append(boxed(",\\quad ".join(t for t in total if t)))
    out.append(para(_products_sentence(c, bi)))

    if any(x != 0 for x in bi.com) or several:
        out.append(subheading(f"{bi.name}: centre of mass and inertia about it"))
        first = f"\\frac{{1}}{{{tex(as_number(num(bi.mass)))}}}\\,{tex(as_number(num(bi.first_moment)))}"
        if not several:
            out.append(display(f"\\mathbf r_G = \\mathbf d = {_value(c, bi.com, LENGTH)}"))
        else:
            out.append(
                display(
                    f"\\mathbf r_G = \\frac{{\\sum_p m_p \\mathbf d_p}}{{m}} = {first} = {_value(c, bi.com, LENGTH)}"
                )
            )
        if not several:
            out.append(
                para(text("The centre of mass is the part's centroid, and "), math("J_G"), text(" its tensor above."))
            )
        elif any(x != 0 for x in bi.com):
            rule = "J_G = J_O - m\\,(|\\mathbf r_G|^2 E - \\mathbf r_G \\mathbf r_G^T)"
            shift = tex(as_number(num(bi.com_shift)))
            result = _value(c, bi.inertia_com, INERTIA)
            # the shift's matrix only where it fits on a line (a symbolic one is shown by its result alone)
            middle = f" = J_O - {shift}" if tex_width(shift) <= SHIFT_WIDTH else ""
            out.append(display(f"{rule}{middle} = {result}"))
        else:
            out.append(para(text("The centre of mass is at O, so "), math("J_G = J_O"), text(".")))
    return out


# --- a composite of several primitives as a teacher tabulates it ------------------------------------------

#: the entries of J about a centroid in a part's table (its shape's axes are the body's)
_DIAGONAL = ("xx", "yy", "zz")


def _tabulated_moments(p: PartInertia) -> dict[str, sp.Expr] | None:
    """A part's J_G,xx, J_G,yy, J_G,zz as formulas in its shape's symbols, when they can be tabulated: a
    primitive whose axes are the body's (a point: all zero); None for a turned or general part."""
    if p.shape is Shape.POINT:
        return dict.fromkeys(_DIAGONAL, sp.S.Zero)
    f = p.formula
    if f is None or f.turned:
        return None
    found: dict[str, sp.Expr] = {}
    for label, formula in f.moments:
        for entry in (x.strip() for x in label.split("=")):
            if entry not in _DIAGONAL:
                return None
            found[entry] = formula
    return found if set(found) == set(_DIAGONAL) else None


def _volume_formula(p: Any) -> tuple[sp.Expr, str] | None:
    """A solid part's volume in its shape's symbols (those of its moments' formulas: ``a b c`` for a box,
    ``\\pi r^2 h`` for a cylinder, ``\\tfrac43 \\pi r^3`` for a sphere), or None (another shape, or no
    formula): checked against the part's volume, so a wrong formula is never printed."""
    f = p.formula
    if f is None or p.volume is None:
        return None
    by_name = {str(sym): sym for sym, _ in f.symbols}
    shape = p.shape.value
    if shape == "box" and {"a", "b", "c"} <= by_name.keys():
        formula, written = by_name["a"] * by_name["b"] * by_name["c"], "a b c"
    elif shape == "cylinder" and {"r", "h"} <= by_name.keys():
        formula, written = sp.pi * by_name["r"] ** 2 * by_name["h"], "\\pi r^{2} h"
    elif shape == "sphere" and "r" in by_name:
        formula, written = sp.Rational(4, 3) * sp.pi * by_name["r"] ** 3, "\\tfrac{4}{3} \\pi r^{3}"
    else:
        return None
    if sp.simplify(formula.subs(dict(f.symbols)) - p.volume) != 0:
        return None
    return formula, written


def _part_tables(c: SolutionContext, bi: BodyInertia) -> list[Block] | None:
    """A body of several primitives (a composite, tutorial p01) in two tables and one aligned sum, the way a
    teacher tabulates it: each part's volume, mass and moments about its own centroid (the formula in its
    shape's symbols over its numbers), then each part's offset d from O and its parallel-axis terms
    m d^2 and -m d_a d_b, then each entry of J_O as the sum of both columns. None when a part cannot be
    tabulated so (one part only, a turned or general part, symbols left in the numbers): the per-part
    working of :func:`_part_blocks` is shown instead."""
    tex, num = c.tex, c.num
    if len(bi.parts) < 2:
        return None
    moments = [_tabulated_moments(p) for p in bi.parts]
    if any(m is None for m in moments):
        return None
    values = [as_number(num(x)) for p in bi.parts for x in (p.mass, *p.centroid, *p.inertia_centroid)]
    values += [as_number(num(sh.term)) for p in bi.parts for sh in p.shifts]
    if any(v.free_symbols for v in values if isinstance(v, sp.Basic)):
        return None

    def number(expr: Any) -> dict[str, str]:
        return math(tex(as_number(num(expr))))

    kg_m2 = "\\ (\\mathrm{kg\\,m^2})"
    has_volume = any(p.volume is not None for p in bi.parts)
    head = [[text("Part")]]
    head += [[math("V\\ (\\mathrm{m^3})")]] if has_volume else []
    head += [[math("m\\ (\\mathrm{kg})")]] + [[math(f"J_{{G,{e}}}{kg_m2}")] for e in _DIAGONAL]
    rows: list[list[list[dict[str, str]]]] = []
    for p, found in zip(bi.parts, moments, strict=True):
        assert found is not None
        f = p.formula
        dims = ""
        if f is not None:
            dims = ",\\ ".join(
                f"{sp.latex(sym)} = {tex(as_number(num(val)))}" for sym, val in f.symbols if str(sym) != "m"
            )
        first = [[text(_part_label(p))]]
        volume_formula = _volume_formula(p)
        first += (
            ([[math(f"\\displaystyle {volume_formula[1]}")]] if volume_formula is not None else [[]])
            if has_volume
            else []
        )
        # the formulas at display size, as a teacher writes them in a table (text style is too small to read)
        density = sp.simplify(p.mass / p.volume) if p.volume is not None and volume_formula is not None else None
        if density is not None and not density.free_symbols & p.volume.free_symbols and density.free_symbols:
            first += [[math(f"\\displaystyle {tex(density)}\\, V")]]  # m = rho V, V in the column before
        else:
            first += [[math(f"\\displaystyle {tex(p.mass)}")]]
        printed = [shape_tex(f, found[e], stacked=True) if f is not None else sp.latex(found[e]) for e in _DIAGONAL]
        first += [[math(f"\\displaystyle {x}")] for x in printed]
        second = [[math(f"{dims}\\ \\mathrm{{m}}")] if dims else []]
        second += [[number(p.volume)] if p.volume is not None else []] if has_volume else []
        second = [
            *second,
            [number(p.mass)],
            *([number(found[e].subs(dict(f.symbols)))] if f else [math("0")] for e in _DIAGONAL),
        ]
        rows += [first, second]
    # a little space before each part's pair of rows (after the first)
    parts_table = {"kind": "table", "header": head, "rows": rows, "gaps": list(range(2, len(rows), 2))}

    shown = [k for k in range(len(ENTRIES)) if any(as_number(num(p.shifts[k].term)) != 0 for p in bi.parts)]
    shift_head = [[text("Part")], [math("\\mathbf d\\ (\\mathrm{m})")]]
    for k in shown:
        label, i, j = ENTRIES[k]
        if i == j:
            d2 = " + ".join(f"d_{AXES[m]}^2" for m in range(3) if m != i)
            shift_head.append([math(f"m\\,({d2})")])
        else:
            shift_head.append([math(f"-m\\,d_{AXES[i]} d_{AXES[j]}")])
    shift_head[-1] = [math(shift_head[-1][0]["tex"] + kg_m2)]
    shift_rows = []
    for p in bi.parts:
        d = ",\\ ".join(tex(as_number(num(x))) for x in p.centroid)
        shift_rows.append([[text(p.name)], [math(f"({d})")], *([number(p.shifts[k].term)] for k in shown)])
    shift_table = {"kind": "table", "header": shift_head, "rows": shift_rows, "gaps": []}

    lines, zeros = [], []
    for k, entry in enumerate(bi.composite):
        label, i, j = ENTRIES[k]
        own = sum((p.inertia_centroid[i, j] for p in bi.parts), sp.S.Zero)
        shift = sum((p.shifts[k].term for p in bi.parts), sp.S.Zero)
        if as_number(num(entry.total)) == 0 and as_number(num(own)) == 0 and as_number(num(shift)) == 0:
            zeros.append(f"J_{{O,{label}}}")
            continue
        term = "m\\,(" + " + ".join(f"d_{AXES[m]}^2" for m in range(3) if m != i) + ")" if i == j else ""
        term = term or f"(-m\\,d_{AXES[i]} d_{AXES[j]})"
        sums = tex(as_number(num(own))) + " + " + _paren(tex(as_number(num(shift))))
        lines.append(
            f"J_{{O,{label}}} = \\textstyle\\sum_p J_{{G,{label}}} + \\sum_p {term} = {sums}"
            f" = {_value(c, entry.total, INERTIA)}"
        )
    out: list[Block] = [
        para(
            text(
                f"{bi.name}: each part about its own centroid, by its shape's formula (the formula in the shape's "
                "symbols, then its numbers):"
            )
        ),
        parts_table,
        para(
            text("Each part's centroid is at "),
            math("\\mathbf d"),
            text(" from O; its parallel-axis terms (the theorem, entry by entry, "),
            math("J_{O,aa} = J_{G,aa} + m\\,d^2"),
            text(", "),
            math("J_{O,ab} = J_{G,ab} - m\\,d_a d_b"),
            text("):"),
        ),
        shift_table,
        para(text(f"{bi.name}: the sum over its parts, about O, from the two tables:")),
        stacked(lines),
    ]
    if zeros:
        out.append(para(math(" = ".join(zeros) + " = 0"), text(" (zero for every part).")))
    return out


def _products_sentence(c: SolutionContext, bi: BodyInertia) -> list[dict[str, str]]:
    """The products of inertia about O and what they say about the body's axes."""
    num = c.num
    nonzero = [(label, v) for label, v in bi.products_origin if as_number(num(v)) != 0]
    if not nonzero:
        return prose("Every product of inertia about O is zero: the body's axes are principal axes of the body at O.")
    shown = ",\\ ".join(f"P_{{{label}}} = -J_{{O,{label}}} = {_value(c, v, INERTIA)}" for label, v in nonzero)
    rest = " The other products are zero." if len(nonzero) < 3 else ""
    return [
        text("Products of inertia about O: "),
        math(shown),
        text(f".{rest} The body's axes are therefore not principal axes of the body at O."),
    ]


def _principal_blocks(c: SolutionContext, point: str, found: Principal) -> list[Block]:
    """The principal moments (eigenvalues of J about the point) and axes (unit eigenvectors, body axes)."""
    where = "the origin O" if point == "O" else "the centre of mass G"
    lines = [
        f"I_{{{point},{k + 1}}} = {c.tex(sp.Float(m))}{unit_tex(INERTIA) if m != 0 else ''}\\ \\text{{along}}\\ "
        f"\\mathbf e_{{{k + 1}}} = {c.tex(sp.Matrix([[sp.Float(x) for x in axis]]))}"
        for k, (m, axis) in enumerate(zip(found.moments, found.axes, strict=True))
    ]
    m = found.moments
    equal = [(k, k + 1) for k in range(2) if abs(m[k + 1] - m[k]) <= 1e-9 * max(abs(m[2]), 1e-300)]
    note: list[Block] = []
    if len(equal) == 2:
        note.append(para(text("The three moments are equal: every axis through the point is a principal axis.")))
    elif equal:
        a, b = equal[0]
        note.append(
            para(
                math(f"I_{{{point},{a + 1}}} = I_{{{point},{b + 1}}}"),
                text(": every axis in the plane of "),
                math(f"\\mathbf e_{{{a + 1}}}, \\mathbf e_{{{b + 1}}}"),
                text(" is a principal axis as well."),
            )
        )
    return [
        para(
            text(f"Principal moments and axes about {where} (the eigenvalues and unit eigenvectors of "),
            math(f"J_{point}"),
            text(", in the body's axes):"),
        ),
        stacked(lines),
        *note,
    ]
