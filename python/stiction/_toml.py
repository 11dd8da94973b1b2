"""Python values as TOML: the values of ``Scene.set`` and whole documents for ``Scene.from_dict``."""

import math
import numbers


def value(v):
    """One TOML value (inline): bool, int, float, str, list/tuple, dict (inline table)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        f = float(v)
        if math.isnan(f):
            return "nan"
        if math.isinf(f):
            return "inf" if f > 0 else "-inf"
        text = repr(f)  # the shortest text that reads back to the same double
        return text if any(c in text for c in ".en") else text + ".0"
    if isinstance(v, str):
        return _string(v)
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {value(x)}" for k, x in v.items()) + " }"
    if hasattr(v, "tolist"):  # NumPy arrays and scalars
        return value(v.tolist())
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(value(x) for x in v) + "]"
    raise TypeError(f"cannot write {type(v).__name__} as a TOML value: {v!r}")


def document(d):
    """A whole document from nested dicts: dicts become tables, lists of dicts arrays of tables."""
    lines = []
    _table(d, [], lines)
    return "\n".join(lines) + "\n"


def _table(d, path, lines):
    simple = {k: v for k, v in d.items() if not _is_table(v) and not _is_table_array(v)}
    if path and (simple or not any(_is_table(v) for v in d.values())):
        lines.append("[" + ".".join(_key(p) for p in path) + "]")
    for k, v in simple.items():
        lines.append(f"{_key(k)} = {value(v)}")
    for k, v in d.items():
        if _is_table(v):
            _table(v, path + [k], lines)
        elif _is_table_array(v):
            for item in v:
                lines.append("[[" + ".".join(_key(p) for p in path + [k]) + "]]")
                for kk, vv in item.items():
                    lines.append(f"{_key(kk)} = {value(vv)}")


def _is_table(v):
    return isinstance(v, dict)


def _is_table_array(v):
    return isinstance(v, (list, tuple)) and len(v) > 0 and all(isinstance(x, dict) for x in v)


def _key(k):
    k = str(k)
    if k and all(c.isalnum() or c in "_-" for c in k) and k.isascii():
        return k
    return _string(k)


def _string(s):
    out = ['"']
    for c in s:
        if c == '"':
            out.append('\\"')
        elif c == "\\":
            out.append("\\\\")
        elif c == "\n":
            out.append("\\n")
        elif c == "\t":
            out.append("\\t")
        elif ord(c) < 0x20 or ord(c) == 0x7F:
            out.append(f"\\u{ord(c):04x}")
        else:
            out.append(c)
    out.append('"')
    return "".join(out)
