"""Figure names as the figure registry (results/figure_registry.json)
declares them: a declared name may hold placeholders, "<n>" for an index and
"<phase>"-like words listed under the registry's "placeholders"; the pattern
of a declaration matches every name it stands for. Shared by the analysis
scripts and the Python module (which the build gives a copy of this file)."""

import re


def name_pattern(name, placeholders):
    """The compiled pattern of the whole names a declared `name` stands for."""
    out = ""
    for part in re.split(r"(<[a-z_]+>)", name):
        if part == "<n>":
            out += r"\d+"
        elif part.startswith("<") and part.endswith(">") and part[1:-1] in placeholders:
            out += "(?:" + "|".join(re.escape(w) for w in placeholders[part[1:-1]]) + ")"
        else:
            out += re.escape(part)
    return re.compile(out + r"\Z")
