"""Real JSON outputs of every command, produced in-process with cheap options (shared by the schema tests).

``python tests/json_outputs.py --write-schemas [NAME ...]`` regenerates stability/schemas/*.json from these outputs (the
structure: required keys, types; a human then tightens where needed), except the hand-written ones
(:data:`HAND_WRITTEN`: every number's unit and the settings tables' ranges), which are edited by hand.  The tests validate fresh outputs against
the committed schemas, so a renamed, dropped or retyped key fails until the schema is updated on purpose.
"""

from __future__ import annotations

import contextlib
import io
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SHEET = ROOT / "docs" / "examples" / "measured_chair_sheet.toml"

#: schema name -> (command, argv) with cheap options (each well under a few seconds warm).
CASES = {
    "critical_speed": ("critical_speed", ["--speeds", "0.5,1"]),
    "compare": ("compare", ["ej-premier", "revised", "--speeds", "0.75"]),
    "simulate": ("simulate", ["--horizon", "0.5", "--sample", "0.1"]),
    "study_critical_impulse": ("study", ["critical-impulse", "--speeds", "0.75", "--horizon", "4"]),
    "study_equal_instability": ("study", ["equal-instability"]),
    "shimmy": ("shimmy", ["--speeds", "1,2", "--chair-model"]),
    "slope": ("slope", ["--cross-slope", "2", "--speed", "1"]),
    "assist": ("assist", ["--speeds", "1,2", "--no-check"]),
    "measure": ("measure", [str(SHEET), "-o", "{tmp}/c.toml"]),
    "tipping": ("tipping", ["--chair", "ej-premier"]),
    "advise": ("advise", []),
    "report": ("report", ["--no-progress"]),
    "sweep": ("sweep", ["{tmp}/g.toml", "-o", "{tmp}/g.csv"]),
    "bench": ("bench", ["--chair", "mid-wheel-drive"]),
    "chair_export": ("chair", ["export", "ej-premier", "--set", "trail=6cm"]),
}
#: Input files a case reads, written into its temporary directory first (name -> {file: text}).
FILES = {
    "sweep": {"g.toml": 'speeds = [0.5, 1.0]\nmeasures = ["growth_rate", "critical_impulse"]\n'
                        '[grid]\ntrail = [0.05, 0.07]\n'},
}
#: Schemas written by hand (units in each number's description, the settings tables' ranges as minimum/maximum,
#: issue 34): ``--write-schemas`` leaves them alone; edit stability/schemas/NAME.json itself.
HAND_WRITTEN = ("critical_speed", "simulate", "advise", "tipping", "bench", "study_critical_impulse",
                "study_equal_instability", "measure", "chair_export", "sweep", "compare", "report", "assist",
                "shimmy", "slope", "assist_layout")
#: The layout forms of commands (a wheel layout instead of the thesis's chair), validated against the same schema.
LAYOUT_CASES = {
    "compare": ("compare", ["ej-premier", "mid-wheel-drive", "--speeds", "0.75"]),
    "shimmy": ("shimmy", ["--chair", "mid-wheel-drive", "--speeds", "1,2"]),
    "slope": ("slope", ["--chair", "mid-wheel-drive", "--cross-slope", "2", "--speed", "1"]),
    "critical_speed": ("critical_speed", ["--chair", "mid-wheel-drive", "--speeds", "0.5,1"]),
    "tipping": ("tipping", ["--chair", "mid-wheel-drive"]),
    "study_critical_impulse": ("study", ["critical-impulse", "--chair", "mid-wheel-drive", "--speeds", "0.75",
                                         "--horizon", "4"]),
    "bench": ("bench", ["--chair", "ej-premier"]),
    "report": ("report", ["--chair", "mid-wheel-drive", "--quick", "--no-progress"]),
    "assist_layout": ("assist", ["--chair", "power-fwd-base", "--speeds=-1,1", "--no-check"]),
}
#: The cases too slow for the default test run (simulations of a study).
SLOW = {"study_equal_instability", "advise", "report"}
#: The layout cases too slow for the default test run (the report's advisor: about 20 s even with --quick).
SLOW_LAYOUT = {"report"}
#: Outputs already computed in this process ((name, layout) -> JSON text): the slow cases run once per worker.
_DONE: dict[tuple[str, bool], str] = {}


def output(name: str, tmp: str, layout: bool = False) -> dict:
    """Run case ``name`` (of :data:`LAYOUT_CASES` with ``layout``) in-process with ``--json``; the decoded JSON."""
    from stability.cli.commands import command_module

    if (name, layout) in _DONE:                 # a fresh copy: callers may change it
        return json.loads(_DONE[name, layout])
    command, argv = (LAYOUT_CASES if layout else CASES)[name]
    for file, text in FILES.get(name, {}).items():
        Path(tmp, file).write_text(text, encoding="utf-8")
    argv = [a.replace("{tmp}", tmp) for a in argv] + ["--json", "--quiet"]
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        status = command_module(command).main(argv)
    assert status == 0, (name, status)
    if not FILES.get(name) and not any("{tmp}" in a for a in (LAYOUT_CASES if layout else CASES)[name][1]):
        _DONE[name, layout] = buf.getvalue()     # depends on its options only, not on the temporary directory
    return json.loads(buf.getvalue())


def infer(value, path: str = ""):
    """A JSON Schema describing ``value``'s structure (keys required, types; numbers may be null)."""
    if isinstance(value, dict):
        if path.endswith("chair_parameters") or path.endswith("parameters") or path.endswith("settings"):
            return {"type": "object"}
        return {"type": "object", "required": sorted(value),
                "properties": {k: infer(v, f"{path}.{k}") for k, v in value.items()}}
    if isinstance(value, list):
        items = [infer(v, path + "[]") for v in value]
        merged = items[0] if items and all(i == items[0] for i in items) else {}
        return {"type": "array", "items": merged} if merged else {"type": "array"}
    if isinstance(value, bool):
        return {"type": "boolean"}
    if isinstance(value, (int, float)):
        return {"type": ["number", "null"]}
    if isinstance(value, str):
        return {"type": ["string", "null"]}
    return {}


def write_schemas(names: list[str] | None = None) -> None:
    """Write the schemas of ``names`` (default: every case) from fresh outputs."""
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        for name, (command, _) in CASES.items():
            if names and name not in names:
                continue
            if name in HAND_WRITTEN:
                print(f"kept {name}.json: hand-written (units and ranges), edit it by hand", file=sys.stderr)
                continue
            data = output(name, tmp)
            doc = {"$schema": "https://json-schema.org/draft/2020-12/schema",
                   "$id": f"stability/schemas/{name}.json",
                   "title": f"python -m stability.{command} --json" + (f" ({name[6:]})" if command == "study" else ""),
                   "description": "JSON output: keys snake_case with the unit last (stability.schemas); "
                                  "arrays over speeds sit next to a speeds_m_s list.",
                   **infer(data)}
            path = ROOT / "stability" / "schemas" / f"{name}.json"
            old = json.loads(path.read_text()) if path.exists() else {}
            if "then" in old:       # a hand-written wheel-layout form: kept, the inferred chair form is its else
                form = {"type": doc["type"], **{k: doc.pop(k) for k in ("required", "properties") if k in doc}}
                doc.update({k: old[k] for k in ("description", "if", "then")}, **{"else": form})
            path.write_text(json.dumps(doc, indent=1) + "\n")
            print(f"wrote {name}.json", file=sys.stderr)


if __name__ == "__main__":
    if "--write-schemas" in sys.argv:      # [NAME ...]: only those schemas
        write_schemas([a for a in sys.argv[1:] if not a.startswith("--")] or None)
