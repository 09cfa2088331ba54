"""Mutant operators of scripts/mutate.sh: the realistic bugs planted one at a time in src/.

Each operator is (name, pattern, replacement). The pattern is a Python regular expression matched against one
source line whose string literals and comments have been blanked out; every match is one mutant, made by
replacing that match alone. A replacement is a string (with \\1-style groups) or a function of the match.
The patterns rely on the project's clang-format style: binary operators have spaces around them, templates
and pointer declarations do not (`a * b`, `a < b`, but `std::vector<int>`, `const T* p`).
"""

# An operand ends here: a name, a number, a closing bracket.
_END = r"(?<=[\w)\]])"
# A float literal: 0.5, 1e-9, 2.0, 1e3 (not an integer, not part of a name).
_FLOAT = r"(?<![\w.])(\d+\.\d*(?:e[-+]?\d+)?|\d+e[-+]?\d+)(?![\w.])"
# A small integer literal that is not part of a name, a float or a subscript-free template argument.
_INT = r"(?<![\w.<])([0-9])(?![\w.>])"
# A simple operand: a name with member accesses and at most one call, e.g. `q`, `rot.q`, `R.transpose()`.
_OPERAND = r"[A-Za-z_][\w.]*(?:\([\w.]*\))?"

OPERATORS = [
    # Arithmetic: a wrong operator.
    ("plus-to-minus", _END + r" \+ ", " - "),
    ("minus-to-plus", _END + r" - ", " + "),
    ("times-to-divide", _END + r" \* ", " / "),
    ("divide-to-times", _END + r" / ", " * "),
    # A dropped term: `a + b * c` becomes `a + 0 * b * c` (the product binds first, so b·c is gone).
    ("drop-added-term", _END + r" \+ (?=[\w(])", " + 0 * "),
    ("drop-subtracted-term", _END + r" - (?=[\w(])", " - 0 * "),
    # A sign: a unary minus dropped.
    ("drop-unary-minus", r"(?<=[(=,?:\[] )-(?=[\w(])|(?<=[(\[])-(?=[\w(])|(?<=return )-(?=[\w(])", ""),
    # Comparisons: a boundary or a direction.
    ("less-to-less-equal", r" < ", " <= "),
    ("less-equal-to-less", r" <= ", " < "),
    ("greater-to-greater-equal", r" > ", " >= "),
    ("greater-equal-to-greater", r" >= ", " > "),
    ("less-to-greater", r" < ", " > "),
    ("greater-to-less", r" > ", " < "),
    ("equal-to-not-equal", r" == ", " != "),
    ("not-equal-to-equal", r" != ", " == "),
    ("and-to-or", r" && ", " || "),
    ("or-to-and", r" \|\| ", " && "),
    ("true-to-false", r"\btrue\b", "false"),
    ("false-to-true", r"\bfalse\b", "true"),
    ("min-to-max", r"\bstd::min\b", "std::max"),
    ("max-to-min", r"\bstd::max\b", "std::min"),
    # Constant factors: ½ becomes 1, a factor 2 becomes 1, any other float constant 1000 times larger.
    ("half-to-one", r"(?<![\w.])0\.5(?![\w.])", "1.0"),
    ("two-to-one", r"(?<![\w.])2(?:\.0)?(?= \*)|(?<=\* )2(?:\.0)?(?![\w.])", "1"),
    ("float-times-1000", _FLOAT, lambda m: f"({m.group(1)} * 1000)"),
    # Off by one: a small integer literal one larger.
    ("int-plus-one", _INT, lambda m: str(int(m.group(1)) + 1)),
    # Frames: a rotation used the wrong way round, or a product in the wrong order (quaternions, matrices).
    ("drop-conjugate", r"\.conjugate\(\)", ""),
    ("drop-transpose", r"\.transpose\(\)", ""),
    ("drop-inverse", r"\.inverse\(\)", ""),
    ("swap-product", r"(?<![\w.):])(" + _OPERAND + r") \* (" + _OPERAND + r")(?![\w(.:])", r"\2 * \1"),
    ("swap-cross", r"(" + _OPERAND + r")\.cross\((" + _OPERAND + r")\)", r"\2.cross(\1)"),
]
