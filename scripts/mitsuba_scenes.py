"""The shared Mitsuba scenes (../shared/scenes/mitsuba/SCENES.txt) by name, for the scripts that
compare caustic with Mitsuba (`speed-vs-mitsuba.py`, `time-to-error.py`)."""
import os
import sys


def scene_list(shared, names):
    listed = [l.strip() for l in open(os.path.join(shared, "scenes/mitsuba/SCENES.txt")) if l.strip()]
    by_name = {os.path.splitext(os.path.basename(p))[0]: p for p in listed}
    if names:
        missing = [n for n in names if n not in by_name]
        if missing:
            sys.exit(f"unknown scenes {missing}; known: {sorted(by_name)}")
        return [(n, by_name[n]) for n in names]
    return list(by_name.items())
