"""What the explorer offers to download: the chair, the results, the eigenvalues, the figure; named after the chair.

* the chair as TOML (:func:`stability.chair.dumps`; it loads back to the same chair),
* the results JSON: exactly what ``python -m stability.critical_speed --chair FILE --json`` prints, built by
  that command's own parser defaults and ``document`` function,
* the eigenvalues against speed as CSV (:func:`stability.app.views.eigenvalues_csv`),
* the toolkit's eigenvalue figure (:func:`stability.plotting.loci.eigenvalues_vs_speed`) as PNG or SVG;
* for a wheel layout (:func:`layout_buttons`): its ``[[wheel]]`` file (:func:`stability.layout.io.dumps`), the
  results JSON of ``critical_speed --chair LAYOUT --json`` and the page's eigenvalues against signed speed as CSV.

Each file is named after the chair (``revised-modified-trail-0.055.toml``): the
name is user text, so only ASCII letters, digits, ``.``, ``-`` and ``_`` are
kept.  Everything here but :func:`download_buttons` is pure Python (no Panel).
"""

from __future__ import annotations

import io
import re
import warnings
from typing import Any

from stability import chair as chair_mod
from stability import tires
from stability.chair import Chair
from stability.runtime.files import json_text, with_tire_range

__all__ = ["chair_toml", "results_json", "figure_file", "file_stem", "file_names", "download_buttons", "STEM_LENGTH",
           "layout_results_json", "layout_buttons"]

#: Longest file-name stem taken from a chair's name (characters).
STEM_LENGTH = 60


def file_stem(name: str) -> str:
    """A file-name stem for a chair named ``name``: ASCII letters, digits, ``.``, ``-``, ``_`` only.

    Parameters
    ----------
    name : str
        The chair's name (any text).

    Returns
    -------
    str
        Runs of other characters become one ``-``; at most :data:`STEM_LENGTH` characters; ``"chair"`` when
        nothing is left.

    Examples
    --------
    >>> file_stem("revised (modified: trail=0.055)")
    'revised-modified-trail-0.055'
    """
    stem = re.sub(r"[^A-Za-z0-9._]+", "-", str(name)).strip("-.")[:STEM_LENGTH].strip("-.")
    return stem or "chair"


def file_names(name: str) -> dict[str, str]:
    """The download file names for a chair named ``name``.

    Parameters
    ----------
    name : str

    Returns
    -------
    dict
        ``"toml"``, ``"json"``, ``"csv"``, ``"png"``, ``"svg"`` -> file name.
    """
    stem = file_stem(name)
    return {"toml": f"{stem}.toml", "json": f"{stem}.results.json", "csv": f"{stem}.eigenvalues.csv",
            "png": f"{stem}.eigenvalues.png", "svg": f"{stem}.eigenvalues.svg"}


def chair_toml(chair: Chair, user: dict | None = None) -> str:
    """The chair as a TOML file (:func:`stability.chair.dumps`; loading it gives the same chair).

    Parameters
    ----------
    chair : Chair
    user : dict, optional
        Its user's ``[user]`` table (the Tracking tab's result), appended as TOML
        (:func:`stability.driver.protocol.user_toml`); the commands' ``--chair`` read it.

    Returns
    -------
    str
    """
    from stability.driver.protocol import user_toml

    return chair_mod.dumps(chair) + (user_toml(user) if user else "")


def results_json(chair: Chair, model: str, user: dict | None = None) -> str:
    """The results JSON: what ``python -m stability.critical_speed --chair <the TOML download> --json`` prints.

    Computed with the command's own defaults (its parser's) and its own
    document builder, so the two cannot drift apart.  With the session's
    user (the ``[user]`` table the TOML download carries) it has the user's
    limits, as the command reads them from that file: the linear limits,
    the assisted limit of a powered chair and the nonlinear lane limit (a
    second or two of simulation).

    Parameters
    ----------
    chair : Chair
    model : {"exact", "thesis"}
    user : dict, optional
        The session's ``[user]`` table (:attr:`stability.app.state.AppState.user`).

    Returns
    -------
    str
    """
    from stability.cli import parse_speeds
    from stability.critical_speed.command import build_parser, document, driver_limits, with_driver_extras
    from stability.driver import Driver
    from stability.linear import analyse
    from stability.models.statics import static_loads
    from stability.study.summary_text import simulator_checks

    args = build_parser().parse_args(["--model", model])
    speeds = parse_speeds(args.speeds)
    with tires.range_policy(args.tire_range), tires.collect_notes() as notes, warnings.catch_warnings():
        warnings.simplefilter("ignore", tires.TireRangeWarning)
        tires.range_check(chair, static_loads(chair))
        summary = analyse(chair, model=model, speeds=speeds, max_speed=args.max_speed)
        driver = human = extras = None
        if user:       # a table without its own source: the command names the file it read, the download's name
            driver = Driver.from_mapping(user, source=f"{file_names(chair.name)['toml']} [user]")
            human, extras = driver_limits(chair, driver, model)
        doc = document(summary, simulator_checks(summary), args, speeds, human=human, driver=driver)
        if extras is not None:
            doc = with_driver_extras(doc, extras)
    return json_text(with_tire_range(doc, notes, args.tire_range)) + "\n"


def figure_file(view: Any, fmt: str) -> io.BytesIO:
    """The toolkit's eigenvalues-against-speed figure (:func:`stability.plotting.loci.eigenvalues_vs_speed`) as a file.

    Parameters
    ----------
    view : LinearView
    fmt : {"png", "svg"}

    Returns
    -------
    io.BytesIO
    """
    from matplotlib.figure import Figure

    from stability.plotting.loci import eigenvalues_vs_speed

    fig = Figure(figsize=(7.5, 7.5), layout="constrained")     # constrained: no title over an axis label
    axes = fig.subplots(2, 1)
    eigenvalues_vs_speed(view.locus, axes, mode_names=view.names,
                         title=f"{view.chair.name}, {view.model} model: eigenvalues against speed")
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=150)
    buf.seek(0)
    return buf


def download_buttons(state: Any, view: Any) -> Any:
    """The download buttons (Panel): chair TOML, results JSON, eigenvalues CSV, the figure as PNG and SVG.

    Parameters
    ----------
    state : AppState
        The session's state (read when a button is pressed).
    view : callable
        ``view() -> LinearView`` of the current chair.

    Returns
    -------
    dict
        Kind (``"toml"``, ``"json"``, ``"csv"``, ``"png"``, ``"svg"``) -> ``panel.widgets.FileDownload``; the page
        sets their ``filename`` from :func:`file_names` when the chair changes.
    """
    import panel as pn

    from stability.app.views import eigenvalues_csv

    work = {"toml": lambda: io.StringIO(state.chair_toml()),
            "json": lambda: io.StringIO(state.results_json()),
            "csv": lambda: io.StringIO(eigenvalues_csv(view())),
            "png": lambda: figure_file(view(), "png"), "svg": lambda: figure_file(view(), "svg")}
    labels = {"toml": "the chair (TOML)", "json": "results (JSON, as critical_speed --json)",
              "csv": "eigenvalues against speed (CSV)", "png": "eigenvalue figure (PNG)",
              "svg": "eigenvalue figure (SVG)"}
    names = file_names(state.chair.name)
    return {k: pn.widgets.FileDownload(callback=fn, filename=names[k], label=labels[k],
                                       css_classes=[f"download-{k}"], width=340)
            for k, fn in work.items()}


def layout_results_json(layout: Any) -> str:
    """What ``python -m stability.critical_speed --chair <this layout> --json`` prints (its default speeds).

    Parameters
    ----------
    layout : stability.layout.Layout

    Returns
    -------
    str
    """
    from stability.critical_speed.command import build_parser, layout_document, layout_summary

    args = build_parser().parse_args([])
    speeds = [float(x) for x in args.speeds.split(",")]
    with tires.range_policy(args.tire_range), tires.collect_notes() as notes, warnings.catch_warnings():
        warnings.simplefilter("ignore", tires.TireRangeWarning)
        doc = layout_document(layout, layout_summary(layout, speeds), speeds)
    return json_text(with_tire_range(doc, notes, args.tire_range)) + "\n"


def layout_buttons(layout: Any, eigenvalues: Any) -> Any:
    """The layout page's download buttons (Panel): the ``[[wheel]]`` file, the results JSON, the eigenvalues CSV.

    Parameters
    ----------
    layout : stability.layout.Layout
    eigenvalues : bokeh.models.ColumnDataSource
        The page's eigenvalue source (``speed`` m/s, ``real`` 1/s), written as drawn.

    Returns
    -------
    dict
        Kind (``"toml"``, ``"json"``, ``"csv"``) -> ``panel.widgets.FileDownload``.
    """
    import panel as pn

    from stability.layout.io import dumps

    def csv() -> io.StringIO:
        d = eigenvalues.data
        rows = ["speed_m_s,real_part_1_s"] + [f"{u!r},{r!r}" for u, r in zip(d["speed"], d["real"], strict=True)]
        return io.StringIO("\n".join(rows) + "\n")

    work = {"toml": lambda: io.StringIO(dumps(layout)), "json": lambda: io.StringIO(layout_results_json(layout)),
            "csv": csv}
    labels = {"toml": "the wheel layout ([[wheel]] TOML)", "json": "results (JSON, as critical_speed --json)",
              "csv": "eigenvalues' real parts against signed speed (CSV)"}
    names = file_names(layout.name)
    return {k: pn.widgets.FileDownload(callback=fn, filename=names[k], label=labels[k],
                                       css_classes=[f"download-{k}"], width=340)
            for k, fn in work.items()}
