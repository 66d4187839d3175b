"""Named example systems, as spec dicts (plain data, the way ``yaml.safe_load`` returns a spec).

Reused by the engine, render and CLI tests, in the manner of sympy's
``sympy/physics/mechanics/models.py``. Turn one into a :class:`tutgen.model.System` with
:func:`system_of`, which goes through the same validation as a spec file.
"""

from __future__ import annotations

import random
from typing import Any

Spec = dict[str, Any]


def system_of(spec: Spec) -> Any:
    """Validate a spec dict into a System (YAML text in, as from a file)."""
    import yaml

    from tutgen.spec.validate import load_system_text

    return load_system_text(yaml.safe_dump(spec, sort_keys=False), path=f"<{spec['title']}>")


def simple_pendulum() -> Spec:
    """A point mass m on a massless rod of length l, swinging in a vertical plane."""
    return {
        "tutgen": 1,
        "title": "Simple pendulum",
        "parameters": ["m", "l", "g"],
        "coordinates": {"theta": {"description": "angle from the downward vertical"}},
        "gravity": [0, "-g", 0],
        "bodies": {"bob": {"mass": "m", "com": [0, "-l", 0]}},
        "joints": {
            "pivot": {"type": "revolute", "parent": "ground", "child": "bob", "axis": "z", "coordinate": "theta"}
        },
    }


def cart_pole() -> Spec:
    """A cart on a horizontal rail carrying a uniform rod pivoted at its end; a force F pushes the cart."""
    return {
        "tutgen": 1,
        "title": "Cart-pole",
        "parameters": ["M", "m", "l", "g", "F"],
        "coordinates": {"x": {"dimension": "length"}, "theta": {"dimension": "angle"}},
        "gravity": [0, "-g", 0],
        "bodies": {
            "cart": {"mass": "M"},
            "pole": {"parts": {"rod": {"shape": "rod", "mass": "m", "length": "l", "axis": "y", "at": [0, "l/2", 0]}}},
        },
        "joints": {
            "rail": {"type": "prismatic", "parent": "ground", "child": "cart", "axis": "x", "coordinate": "x"},
            "hinge": {"type": "revolute", "parent": "cart", "child": "pole", "axis": "z", "coordinate": "theta"},
        },
        "loads": {"push": {"body": "cart", "force": ["F", 0, 0]}},
    }


def double_pendulum() -> Spec:
    """Two point masses on massless rods, the second angle measured relative to the first link."""
    return {
        "tutgen": 1,
        "title": "Double pendulum",
        "parameters": ["m1", "m2", "l1", "l2", "g"],
        "coordinates": ["theta1", "theta2"],
        "gravity": [0, "-g", 0],
        "bodies": {
            "bob1": {"mass": "m1", "com": [0, "-l1", 0]},
            "bob2": {"mass": "m2", "com": [0, "-l2", 0]},
        },
        "joints": {
            "shoulder": {"type": "revolute", "parent": "ground", "child": "bob1", "axis": "z", "coordinate": "theta1"},
            "elbow": {
                "type": "revolute",
                "parent": "bob1",
                "child": "bob2",
                "axis": "z",
                "origin": [0, "-l1", 0],
                "coordinate": "theta2",
            },
        },
    }


def _number(rng: random.Random, low: float, high: float) -> float:
    """A random number with two decimals (read back as an exact rational)."""
    return round(rng.uniform(low, high), 2)


def planar_chain(n: int, seed: int, *, conservative: bool = True) -> Spec:
    """An n-link serial chain in the x-y plane with random joint types and random positive data.

    Each joint is revolute (about z) or prismatic (along the parent's x or y); link i reaches from its
    joint to the next one at [l_i, 0, 0] and is a point mass at its tip, a uniform rod, or both. Gravity
    is along -y. Some chains carry a spring between the ground and the last link. With
    ``conservative=False`` every coordinate also gets a viscous damper and a generalized force, and
    the last link a force at its tip.
    """
    rng = random.Random(seed)
    bodies: dict[str, Any] = {}
    joints: dict[str, Any] = {}
    coordinates: dict[str, Any] = {}
    lengths = []
    for i in range(1, n + 1):
        link, q = f"link{i}", f"q{i}"
        length = _number(rng, 0.3, 2.0)
        lengths.append(length)
        kind = rng.choice(["revolute", "prismatic"])
        joint: dict[str, Any] = {"type": kind, "parent": "ground" if i == 1 else f"link{i - 1}", "child": link}
        joint["axis"] = "z" if kind == "revolute" else rng.choice(["x", "y"])
        joint["coordinate"] = q
        if i > 1:
            joint["origin"] = [lengths[-2], 0, 0]
        joints[f"joint{i}"] = joint
        coordinates[q] = {"dimension": "angle" if kind == "revolute" else "length"}
        style = rng.choice(["tip", "rod", "both"])
        parts: dict[str, Any] = {}
        if style in ("rod", "both"):
            parts["rod"] = {
                "shape": "rod",
                "mass": _number(rng, 0.5, 3.0),
                "length": length,
                "axis": "x",
                "at": [length / 2, 0, 0],
            }
        if style in ("tip", "both"):
            parts["tip"] = {"shape": "point", "mass": _number(rng, 0.5, 3.0), "at": [length, 0, 0]}
        bodies[link] = {"parts": parts}
    spec: Spec = {
        "tutgen": 1,
        "title": f"Planar chain n={n} seed={seed}",
        "coordinates": coordinates,
        "gravity": [0, -_number(rng, 1.0, 10.0), 0],
        "bodies": bodies,
        "joints": joints,
    }
    if rng.random() < 0.5:
        spec["springs"] = {
            "anchor": {
                "stiffness": _number(rng, 0.5, 5.0),
                "between": [{"body": "ground", "at": [0, _number(rng, 0.5, 2.0), 0]}, {"body": f"link{n}"}],
                "free_length": _number(rng, 0.1, 1.0),
            }
        }
    if not conservative:
        spec["dampers"] = {
            f"d{i}": {"coefficient": _number(rng, 0.1, 2.0), "extension": q} for i, q in enumerate(coordinates, 1)
        }
        spec["generalized_forces"] = {q: _number(rng, -2.0, 2.0) for q in coordinates}
        spec["loads"] = {
            "tip_force": {
                "body": f"link{n}",
                "force": [_number(rng, -2.0, 2.0), _number(rng, -2.0, 2.0), 0],
                "at": [lengths[-1], 0, 0],
            }
        }
    return spec


def feature_tour() -> Spec:
    """A contrived 3-DOF system that uses the spec features the example specs leave out.

    A joint ``orientation`` and ``offset``, a ``fixed`` joint, a body given by ``mass``/``com``/``inertia``
    with products of inertia, a hollow cylinder with a tilted axis, a thin cylinder and an off-centre disc,
    a load in the body frame with a reaction on another body, forces and torques that depend on a
    velocity, a spring between two moving bodies, a damper to the ground, and a numeric parameter with
    a unit.
    """
    return {
        "tutgen": 1,
        "title": "Feature tour",
        "parameters": {
            "m1": None,
            "m2": None,
            "m3": None,
            "a": None,
            "b": None,
            "r": None,
            "g": {"value": "9.81 m/s^2"},
            "k": None,
            "c": None,
            "F": None,
            "tau": None,
            "J1": None,
            "J2": None,
            "J3": None,
            "P": None,
        },
        "coordinates": {"phi": {"dimension": "angle"}, "s": {"dimension": "length"}, "psi": {"dimension": "angle"}},
        "gravity": {"g": "g", "direction": "-z"},
        "bodies": {
            "base": {
                "mass": "m1",
                "com": ["a/3", 0, "b/4"],
                "inertia": {"xx": "J1", "yy": "J2", "zz": "J3", "xy": "-P", "xz": "P/2", "yz": 0},
            },
            "slider": {
                "parts": {
                    "sleeve": {
                        "shape": "hollow_cylinder",
                        "mass": "m2",
                        "outer_radius": "r",
                        "inner_radius": "r/2",
                        "length": "a",
                        "axis": [1, 1, 0],
                    },
                }
            },
            "bracket": {"parts": {"lug": {"shape": "point", "mass": "m3/4", "at": [0, "b", 0]}}},
            "wheel": {
                "parts": {
                    "rim": {"shape": "thin_cylinder", "mass": "m3", "radius": "r", "length": "b", "axis": "x"},
                    "hub": {"shape": "disc", "mass": "m3/2", "radius": "r/2", "axis": "y", "at": [0, 0, "r/5"]},
                }
            },
        },
        "joints": {
            "yaw": {
                "type": "revolute",
                "parent": "ground",
                "child": "base",
                "axis": "z",
                "offset": "30 deg",
                "coordinate": "phi",
            },
            "slide": {
                "type": "prismatic",
                "parent": "base",
                "child": "slider",
                "axis": "x",
                "origin": ["a", 0, "b"],
                "orientation": [{"axis": "z", "angle": "90 deg"}, {"axis": "x", "angle": "pi/3"}],
                "offset": "b",
                "coordinate": "s",
            },
            "mount": {
                "type": "fixed",
                "parent": "slider",
                "child": "bracket",
                "origin": [0, 0, "r"],
                "orientation": [{"axis": "y", "angle": "-pi/2"}],
            },
            "spin": {
                "type": "revolute",
                "parent": "bracket",
                "child": "wheel",
                "axis": "-y",
                "origin": [0, "b", 0],
                "coordinate": "psi",
            },
        },
        "springs": {
            "tie": {
                "stiffness": "k",
                "between": [{"body": "base", "at": [0, "a", 0]}, {"body": "slider", "at": ["r", 0, 0]}],
            }
        },
        "dampers": {"drag": {"coefficient": "c", "between": ["ground", {"body": "slider", "at": [0, 0, "r"]}]}},
        "loads": {
            "drive": {"body": "wheel", "torque": [0, "tau", 0], "frame": "body", "reaction_body": "bracket"},
            "pull": {"body": "slider", "force": ["F", 0, "-c*s_dot"], "at": [0, "r", 0], "reaction_body": "base"},
            "twist": {"body": "base", "torque": [0, 0, "-c*phi_dot"]},
        },
    }


def explicit_top() -> Spec:
    """The heavy top of specs/examples, placed by an explicit z-x-z orientation instead of joints,
    with a damping torque about its axis in the body frame and a tilted gravity."""
    return {
        "tutgen": 1,
        "title": "Top with an explicit orientation",
        "parameters": ["m", "R", "h", "l", "g", "c"],
        "coordinates": ["psi", "theta", "phi"],
        "gravity": {"g": "g", "direction": [1, 0, -3]},
        "bodies": {
            "top": {
                "parts": {
                    "cylinder": {"shape": "cylinder", "mass": "m", "radius": "R", "length": "h", "at": [0, 0, "l"]}
                },
                "orientation": [
                    {"axis": "z", "angle": "psi"},
                    {"axis": "x", "angle": "theta"},
                    {"axis": "z", "angle": "phi"},
                ],
            }
        },
        "loads": {"drag": {"body": "top", "torque": [0, 0, "-c*phi_dot"], "frame": "body"}},
    }


def slider_in_explicit_tube() -> Spec:
    """A tube turned by an explicit orientation (two rotations about z, which must add up) carrying a
    slider on a prismatic joint, and a pendulum on the slider whose axis is -z."""
    return {
        "tutgen": 1,
        "title": "Slider in an explicitly turned tube",
        "parameters": ["M", "L", "m", "m2", "l", "g", "tau"],
        "coordinates": ["phi", "r", "beta"],
        "gravity": [0, "-g", 0],
        "bodies": {
            "tube": {
                "parts": {"rod": {"shape": "rod", "mass": "M", "length": "L"}},
                "orientation": [{"axis": "z", "angle": "phi"}, {"axis": "z", "angle": "pi/6"}],
            },
            "slider": {"mass": "m"},
            "arm": {"parts": {"rod": {"shape": "rod", "mass": "m2", "length": "l", "at": ["l/2", 0, 0]}}},
        },
        "joints": {
            "slot": {"type": "prismatic", "parent": "tube", "child": "slider", "axis": "x", "coordinate": "r"},
            "pin": {"type": "revolute", "parent": "slider", "child": "arm", "axis": "-z", "coordinate": "beta"},
        },
        "loads": {"motor": {"body": "arm", "torque": [0, 0, "tau"], "reaction_body": "slider"}},
    }


def absolute_chain() -> Spec:
    """A planar 3R arm whose last joint angle is absolute (belt-driven from the base) and whose
    second joint turns about -z, under gravity along -y."""
    return {
        "tutgen": 1,
        "title": "3R arm with an absolute last angle",
        "parameters": ["m1", "m2", "m3", "l1", "l2", "l3", "g"],
        "coordinates": ["t1", "t2", "t3"],
        "gravity": [0, "-g", 0],
        "bodies": {
            "link1": {"parts": {"rod": {"shape": "rod", "mass": "m1", "length": "l1", "at": ["l1/2", 0, 0]}}},
            "link2": {"mass": "m2", "com": ["l2", 0, 0]},
            "link3": {"parts": {"rod": {"shape": "rod", "mass": "m3", "length": "l3", "at": ["l3/2", 0, 0]}}},
        },
        "joints": {
            "j1": {"type": "revolute", "parent": "ground", "child": "link1", "axis": "z", "coordinate": "t1"},
            "j2": {
                "type": "revolute",
                "parent": "link1",
                "child": "link2",
                "axis": "-z",
                "origin": ["l1", 0, 0],
                "coordinate": "t2",
            },
            "j3": {
                "type": "revolute",
                "parent": "link2",
                "child": "link3",
                "axis": "z",
                "origin": ["l2", 0, 0],
                "coordinate": "t3",
                "angle": "absolute",
            },
        },
    }


def spec_models() -> dict[str, Spec]:
    """Every named system above, by a readable id (a few chains with fixed seeds)."""
    return {
        "simple-pendulum": simple_pendulum(),
        "cart-pole": cart_pole(),
        "double-pendulum": double_pendulum(),
        "feature-tour": feature_tour(),
        "explicit-top": explicit_top(),
        "slider-in-explicit-tube": slider_in_explicit_tube(),
        "absolute-chain": absolute_chain(),
        **{f"planar-chain-{n}-{seed}": planar_chain(n, seed, conservative=False) for n, seed in ((2, 1), (3, 7))},
    }


def negative_length() -> Spec:
    """A slider placed at [d*x, 0, 0] with a numeric d = -1, tied to the origin by a spring of free length 1.

    The spring's length is |d x| = |x|, so U = (|x| - 1)^2 / 2 and Q = -(x - sign(x)).
    """
    return {
        "tutgen": 1,
        "title": "Negative parameter value",
        "parameters": {"d": -1},
        "coordinates": ["x"],
        "bodies": {"slider": {"mass": 1, "position": ["d*x", 0, 0]}},
        "springs": {"s": {"stiffness": 1, "between": ["ground", "slider"], "free_length": 1}},
    }


def quadratic_drag() -> Spec:
    """A block on a spring with a drag force -c x_dot |x_dot| and a generalized force that is not
    polynomial in the velocity either."""
    return {
        "tutgen": 1,
        "title": "Quadratic drag",
        "parameters": ["m", "k", "c"],
        "coordinates": ["x"],
        "bodies": {"block": {"mass": "m", "position": ["x", 0, 0]}},
        "springs": {"s": {"stiffness": "k", "extension": "x"}},
        "loads": {"drag": {"body": "block", "force": ["-c*x_dot*abs(x_dot)", 0, 0]}},
        "generalized_forces": {"x": "-c*x_dot*sqrt(1 + x_dot^2)"},
    }
