"""What tables and plots call a swept value, a sweep point and a pair of axes.

A swept value may be a whole JSON object (a zip over device files swaps the
whole /display or /pipeline): results.csv holds it as JSON text, which is no
tick label or legend. Such values are named by the keys in which they differ
from the axis's other values ("lit_ms=0.48, type=global"), cut to LABEL_CHARS;
failing that, by the axis's name and the value's position ("/pipeline 2").
No label made here for a JSON value holds a brace or a bracket. Plain values
are kept whole (a table shows them); plots cut what they draw with cut().
"""

import json

# Longer labels would make a plot's legend or ticks wider than the plot.
LABEL_CHARS = 40


def parse(text):
    """A swept value as results.csv writes it: the JSON object or array it holds, else the text."""
    text = str(text)
    if text.lstrip().startswith(("{", "[")):
        try:
            return json.loads(text)
        except ValueError:
            return text
    return text


def is_structured(text):
    return isinstance(parse(text), (dict, list))


def _leaves(value, path=()):
    """{key path: scalar} of a JSON value (dict keys and list indices)."""
    if isinstance(value, dict):
        items = value.items()
    elif isinstance(value, list):
        items = enumerate(value)
    else:
        return {path: value}
    out = {}
    for key, item in items:
        out.update(_leaves(item, path + (str(key),)))
    return out


def _shortest_names(paths):
    """{key path: the shortest tail of it that no other path ends with}."""
    names = {}
    for path in paths:
        for n in range(1, len(path) + 1):
            tail = path[-n:]
            if n == len(path) or sum(1 for p in paths if p[-n:] == tail) == 1:
                names[path] = ".".join(tail)
                break
    return names


def _scalar_text(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "absent"
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    return str(value)


def cut(text, chars=LABEL_CHARS):
    """Text no longer than `chars`, ending in an ellipsis when cut."""
    text = str(text)
    return text if len(text) <= chars else text[:chars - 1].rstrip(", ") + "\u2026"


def value_labels(values, axis_name):
    """{value text: label} for one axis's distinct values (results.csv text)."""
    parsed = {v: parse(v) for v in values}
    if not any(isinstance(p, (dict, list)) for p in parsed.values()):
        return {v: v for v in values}  # plain text: tables show it whole, plots cut it
    leaves = {v: _leaves(p) for v, p in parsed.items()}
    paths = sorted({k for leaf in leaves.values() for k in leaf})
    differing = [k for k in paths if len({json.dumps(leaf.get(k), sort_keys=True) for leaf in leaves.values()}) > 1]
    names = _shortest_names(differing)
    labels = {}
    for i, v in enumerate(values):
        text = ", ".join(f"{names[k]}={_scalar_text(leaves[v].get(k))}" for k in differing)
        labels[v] = cut(text) if text else f"{cut(axis_name, LABEL_CHARS - 4)} {i + 1}"
    # Two values cut to one label would be drawn as one: number them instead.
    if len(set(labels.values())) < len(labels):
        labels = {v: f"{cut(axis_name, LABEL_CHARS - 4)} {i + 1}" for i, v in enumerate(values)}
    return labels


def distinct(rows, axis):
    """An axis's values in plan order of first appearance."""
    return list(dict.fromkeys(row.axis_values[axis] for row in rows))


def crossed(rows, axis_a, axis_b):
    """Whether every value of one axis meets every value of the other (a Cartesian pair of varied axes)."""
    values_a, values_b = distinct(rows, axis_a), distinct(rows, axis_b)
    if len(values_a) < 2 or len(values_b) < 2:
        return False
    pairs = {(r.axis_values[axis_a], r.axis_values[axis_b]) for r in rows}
    return len(pairs) == len(values_a) * len(values_b)


def varied_axes(rows, axes):
    return [a for a in axes if len(distinct(rows, a)) > 1]


def is_zip(rows, axes):
    """Two or more varied axes of which no two are crossed: the points are a list, not a grid."""
    varied = varied_axes(rows, axes)
    return len(varied) > 1 and not any(crossed(rows, a, b) for i, a in enumerate(varied) for b in varied[i + 1:])


def named(axis_name, label, value):
    """'name=value', or for a JSON value (whose label is itself key=value pairs) 'name (label)'."""
    return f"{axis_name} ({label})" if is_structured(value) else f"{axis_name}={label}"


def point_labels(values_by_point, axes, label_of_axis, labels_by_axis):
    """A name per point ({axis: value text} each): the plain values of the axes that have them (a
    /description swept alone or beside whole objects names the point by itself), else every axis's label."""
    if not axes:
        return ["base scenario" for _ in values_by_point]
    plain = [a for a in axes if not any(is_structured(v[a]) for v in values_by_point)]
    shown = plain or axes
    names = []
    for values in values_by_point:
        # A swept /description says what the point is: it needs no "name=" before it.
        if len(shown) == 1 and (len(axes) > 1 or shown[0] == "/description"):
            names.append(labels_by_axis[shown[0]][values[shown[0]]])
        else:
            names.append(", ".join(named(label_of_axis(a), labels_by_axis[a][values[a]], values[a]) for a in shown))
    return names
