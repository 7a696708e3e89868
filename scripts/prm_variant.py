"""Variants of a ritr scene file: the same .prm with some entries set to other values.

An override names its entry by path, "Body 0/refinements" or "end time"; entries the file
does not set are added to their subsection (created if needed). Relative `file` entries are
made absolute, so that the variant can be written anywhere.
"""
import os
import re

SET = re.compile(r"^(\s*)set\s+(.+?)\s*=\s*(.*?)\s*(#.*)?$")


def _split(path):
    parts = path.split("/")
    return tuple(parts[:-1]), parts[-1]


def entries(text):
    """{path: value} of every `set` in a .prm text."""
    found, stack = {}, []
    for line in text.splitlines():
        stripped = line.split("#", 1)[0].strip()
        if stripped.startswith("subsection "):
            stack.append(stripped[len("subsection "):].strip())
        elif stripped == "end" and stack:
            stack.pop()
        else:
            m = SET.match(line)
            if m:
                found["/".join(stack + [m.group(2)])] = m.group(3)
    return found


def variant(text, overrides, base_directory):
    """The .prm text with `overrides` ({path: value}) applied."""
    pending = {}
    for path, value in overrides.items():
        section, key = _split(path)
        pending.setdefault(section, {})[key] = str(value)
    out, stack = [], []

    def flush(section, indent):
        for key, value in pending.pop(section, {}).items():
            out.append(f"{indent}set {key} = {value}")

    for line in text.splitlines():
        stripped = line.split("#", 1)[0].strip()
        if stripped.startswith("subsection "):
            stack.append(stripped[len("subsection "):].strip())
            out.append(line)
            continue
        if stripped == "end" and stack:
            flush(tuple(stack), "  " * len(stack))
            stack.pop()
            out.append(line)
            continue
        m = SET.match(line)
        if m:
            section, key = tuple(stack), m.group(2)
            value = m.group(3)
            if key in pending.get(section, {}):
                value = pending[section].pop(key)
            elif key == "file" and value and not os.path.isabs(value):
                value = os.path.normpath(os.path.join(base_directory, value))
            out.append(f"{m.group(1)}set {key} = {value}")
            continue
        out.append(line)
    flush((), "")
    for section in list(pending):
        depth = 0
        for depth, name in enumerate(section):
            out.append("  " * depth + f"subsection {name}")
        flush(section, "  " * len(section))
        for depth in reversed(range(len(section))):
            out.append("  " * depth + "end")
    return "\n".join(out) + "\n"


def write_variant(scene, overrides, destination):
    """Writes `scene` with `overrides` to `destination` and returns its path."""
    with open(scene) as f:
        text = f.read()
    with open(destination, "w") as f:
        f.write(variant(text, overrides, os.path.dirname(os.path.abspath(scene))))
    return destination
