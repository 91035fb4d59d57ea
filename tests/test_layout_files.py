"""A wheel layout written as a chair file (``stability.layout.io.dumps``, ``python -m stability.chair export``) and
read back (``load_layout``): the same layout exactly, every field, anti-tip contacts included.

Exact equality is the claim: floats are written by ``repr`` (the shortest string that reads back to the same
double), so no tolerance applies.
"""

from __future__ import annotations

import dataclasses

import pytest

from stability.chair import preset
from stability.layout import Layout
from stability.layout.io import dumps, load_layout
from stability.layout.presets import layout_preset, layout_preset_names


def _round_trip(layout: Layout, tmp_path) -> Layout:
    f = tmp_path / "layout.toml"
    f.write_text(dumps(layout))
    return load_layout(f)


@pytest.mark.parametrize("name", layout_preset_names())
def test_every_layout_preset_reads_back_exactly(name, tmp_path):
    layout = layout_preset(name)
    assert _round_trip(layout, tmp_path) == layout


def test_a_short_form_chair_with_anti_tip_devices_and_odd_values_reads_back(tmp_path):
    """The E&J expanded (its anti-tip contacts from ``anti_tip_reach``), with values that have no short decimal."""
    chair = preset("ej-premier").replace(anti_tip_reach=0.1, trail=0.1 / 3.0, m=80.0 + 1e-9)
    layout = Layout.from_chair(chair)
    assert len(layout.anti_tip) == 2
    back = _round_trip(layout, tmp_path)
    assert back == layout
    # every field of every wheel is in the file, so a user edits what is there instead of guessing names
    text = dumps(layout)
    for w in (*layout.wheels, *layout.casters):
        for f in dataclasses.fields(w):
            if getattr(w, f.name) is not None:
                assert f"\n{f.name} = " in text


def test_a_bad_anti_tip_table_is_named(tmp_path):
    text = dumps(layout_preset("mid-wheel-drive")) + "\n[[anti_tip]]\nx = -0.4\n"
    f = tmp_path / "bad.toml"
    f.write_text(text)
    with pytest.raises(ValueError, match=r"each \[\[anti_tip\]\] table needs exactly x and y"):
        load_layout(f)
    f.write_text(text + "y = 3.0\n")
    with pytest.raises(ValueError, match="anti_tip y"):
        load_layout(f)


def test_chair_export_writes_a_layout_in_the_wheel_form(tmp_path, capsys):
    from stability.chair.__main__ import main

    out = tmp_path / "mwd.toml"
    assert main(["export", "mid-wheel-drive", "-o", str(out)]) == 0
    assert load_layout(out) == layout_preset("mid-wheel-drive")
    assert main(["export", "mid-wheel-drive", "--wheels"]) == 0
    assert main(["export", str(out)]) == 0                      # a [[wheel]] file exports as itself
    assert capsys.readouterr().out.count("\n[[wheel]]\n") == 12                # 6 wheels, twice
    # a short-form chair expanded into its wheels with --wheels; written short otherwise
    assert main(["export", "ej-premier", "--wheels", "-o", str(out)]) == 0
    assert load_layout(out) == Layout.from_chair(preset("ej-premier"))
    capsys.readouterr()
    assert main(["export", "ej-premier"]) == 0
    assert "\n[[wheel]]\n" not in capsys.readouterr().out
    assert main(["list"]) == 0
    names = capsys.readouterr().out.split()
    assert set(layout_preset_names()) <= set(names) and "ej-premier" in names


@pytest.mark.parametrize("argv, words", [
    (["export", "mid-wheel-drive", "--set", "trail=0.06"], "'trail' is not a field of layout"),
    (["export", "mid-wheel-drive", "--json"], "--json is for the short form's chair"),
])
def test_chair_export_refuses_short_form_options_for_a_layout(argv, words, capsys):
    from stability.chair.__main__ import main

    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and words in err[0]
