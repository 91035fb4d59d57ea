"""``-o FILE`` of ``slope`` and ``critical_speed``: the figure is written in the format its suffix names, its
title names chair and model, its caption's numbers are the command's, and an unknown suffix is refused (exit 2,
one line, nothing written).  In-process, one run per command."""

from __future__ import annotations

import json

import pytest

from stability.report.document import figure_texts


@pytest.fixture
def captured(monkeypatch):
    """Record the figures the commands save (the real save still runs)."""
    from stability.runtime import files as output

    figs = []
    real = output.save_figure

    def save(fig, path, **kw):
        figs.append(fig)
        return real(fig, path, **kw)

    monkeypatch.setattr(output, "save_figure", save)
    return figs


def _squash(texts):
    return " ".join(" ".join(texts).split())


def test_slope_figure_is_written_with_the_commands_numbers(tmp_path, captured, capsys):
    from stability.slope.__main__ import main

    out = tmp_path / "slope.png"
    assert main(["--cross-slope", "2", "--speed", "1", "-o", str(out), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and [p.name for p in tmp_path.iterdir()] == ["slope.png"]
    (fig,) = captured
    text = _squash(figure_texts(fig))
    assert "ej-premier | exact model | cross slope 2 deg at 1 m/s" in text
    assert "cross slope (deg)" in text and "holding yaw moment (N m)" in text and "time t (s)" in text
    # the caption quotes the command's own holding moment and hand-rim difference (3 significant figures)
    assert f"{data['holding_yaw_moment_N_m']:.3g} N m of yaw moment" in text
    drive = data["drive_forces"]
    assert f"{abs(drive['handrim_force_difference_N']):.3g} N with the {drive['harder_side']} wheel" in text
    assert f"turns {data['uncorrected_turn']}" in text and "What to conclude" in text
    assert fig.axes[0].get_legend() is not None


def test_critical_speed_figure_is_written_with_the_commands_critical_speeds(tmp_path, captured, capsys):
    from stability.critical_speed.command import main

    out = tmp_path / "cs.svg"
    assert main(["--chair", "revised", "--model", "thesis", "-o", str(out), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert out.read_text().lstrip().startswith("<?xml") and "<svg" in out.read_text()
    (fig,) = captured
    text = _squash(figure_texts(fig))
    assert "revised | thesis model | eigenvalues against speed" in text
    assert "real part σ (1/s)" in text and "forward speed U (m/s)" in text and "What to conclude" in text
    locked = [c["speed_m_s"] for c in data["locked_casters"]["crossings"]]
    assert locked and all(f"{u:.3g} m/s" in text for u in locked)


@pytest.mark.parametrize("command,argv", [
    ("slope", ["--cross-slope", "2", "--speed", "1"]),
    ("critical_speed", []),
])
def test_unknown_suffix_is_refused_before_any_work(command, argv, tmp_path, capsys):
    from stability.cli.commands import command_module

    out = tmp_path / "fig.jpg"
    assert command_module(command).main(argv + ["-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == f"error: -o {str(out)!r} is invalid; the suffix names the format, valid: .pdf, .png, .svg"
    assert list(tmp_path.iterdir()) == []
