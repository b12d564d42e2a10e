"""Labels of a sweep's runs from its varied keys, for legends and tables.

Each varied key is named by its last word (the last part of the dotted key, two parts when
two varied keys end alike: "x.start", "y.start") and its value is written in a unit that
reads well, from the key's unit in docs/reference/scene-keys.md: metres in mm (µm below
0.1 mm), seconds in ms or µs, pascals in kPa. One item per varied key, joined by commas:
"thickness = 0.5 mm", "mach = 1.75", "arrangement = columnar".

The summary's columns name the keys as identifiers (particles_layer_thickness); the dotted
key is found in the run's scene.resolved.toml, which holds every key the run read.
"""
import os
import re
import tomllib

REFERENCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "reference", "scene-keys.md")


def identifier(key):
    """A dotted key as the summary's column names it (sweep_summary.cpp: non-alphanumerics to _)."""
    return re.sub(r"[^0-9A-Za-z]", "_", key)


def varied_columns(summary):
    """The summary's columns of varied keys (between `run` and `run_index_1`)."""
    header = list(summary)
    return header[1:header.index("run_index_1")]


def scene_keys(resolved_path):
    """Every dotted key with a value in a resolved scene (arrays of tables left out)."""
    try:
        with open(resolved_path, "rb") as f:
            scene = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError):
        return []
    keys = []

    def walk(table, prefix):
        for name, value in table.items():
            key = prefix + name
            if isinstance(value, dict):
                walk(value, key + ".")
            else:
                keys.append(key)
    walk(scene, "")
    return keys


def dotted_keys(sweepdir, summary, columns):
    """{column: dotted key} from the runs' resolved scenes; the column itself when none names it."""
    found = {}
    for run in summary["run"]:
        for key in scene_keys(os.path.join(sweepdir, run, "scene.resolved.toml")):
            if identifier(key) in columns:
                found.setdefault(identifier(key), key)
        if len(found) == len(columns):
            break
    return {c: found.get(c, c) for c in columns}


def key_units(reference=REFERENCE):
    """[(pattern, unit)] of the key reference's rows."""
    units = []
    try:
        with open(reference, encoding="utf-8") as f:
            for line in f:
                m = re.match(r"\| `([^`]+)` \| [^|]* \| ([^|]*) \|", line)
                if m:
                    units.append((m.group(1), m.group(2).strip()))
    except OSError:
        pass
    return units


def unit_of(key, units):
    """The unit of a dotted key (a row's `*` matches any one part); "" when unknown."""
    parts = key.split(".")
    for pattern, unit in units:
        p = pattern.split(".")
        if len(p) == len(parts) and all(a in ("*", b) for a, b in zip(p, parts)):
            return unit
    return ""


def value_text(text, unit):
    """A value as written in the summary, in a unit that reads well ("0.0005", "m" -> "0.5 mm")."""
    try:
        v = float(text)
    except ValueError:
        return text
    a = abs(v)
    if unit == "m":
        scale, shown = (1e6, "µm") if 0 < a < 1e-4 else (1e3, "mm")
    elif unit == "s":
        scale, shown = (1e6, "µs") if 0 < a < 1e-4 else (1e3, "ms") if a < 1 else (1.0, "s")
    elif unit == "Pa":
        scale, shown = (1e-3, "kPa") if a >= 1e3 else (1.0, "Pa")
    elif unit in ("", "1"):
        scale, shown = 1.0, ""
    else:
        scale, shown = 1.0, unit
    number = "%.6g" % (v * scale)
    return number + (" " + shown if shown else "")


def short_names(keys):
    """The last word of each key, with more words where two would read alike."""
    words = {k: 1 for k in keys}
    while True:
        names = {k: ".".join(k.split(".")[-words[k]:]) for k in keys}
        clash = [k for k in keys if list(names.values()).count(names[k]) > 1 and words[k] < len(k.split("."))]
        if not clash:
            return names
        for k in clash:
            words[k] += 1


def run_labels(sweepdir, summary):
    """One label per run (summary row): "<last word> = <value unit>" per varied key."""
    columns = varied_columns(summary)
    keys = dotted_keys(sweepdir, summary, columns)
    names = short_names(list(keys.values()))
    units = key_units()
    labels = []
    for k in range(len(summary["run"])):
        items = ["%s = %s" % (names[keys[c]], value_text(summary[c][k], unit_of(keys[c], units))) for c in columns]
        labels.append(", ".join(items) if items else summary["run"][k])
    return labels
