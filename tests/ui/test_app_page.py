"""The explorer's page object without a browser (needs the ``app`` extra; runs in the ui step)."""

from __future__ import annotations

import pathlib

import numpy as np
import pytest

from stability import chair as chair_mod

pytestmark = pytest.mark.ui
pytest.importorskip("panel")

EXAMPLES = pathlib.Path(__file__).parents[2] / "docs" / "examples"


def test_uncertainty_band_is_the_linear_intervals():
    from stability.app.page import Explorer
    from stability.linear.intervals import linear_intervals
    from stability.uncertainty import load_uncertainty

    ex = Explorer(auto_nonlinear=False)
    path = EXAMPLES / "measured_chair.uncertainty.toml"
    assert ex.state.load_uncertainty(path.read_bytes(), path.name) is None
    ex._start_bands()
    ex.jobs._futures[-1].result(timeout=600)
    data = ex.speed_tab.unc_src.data
    speeds = np.asarray(data["speed"])
    want = linear_intervals(chair_mod.preset("ej-premier"), load_uncertainty(path), speeds=speeds, samples=300,
                            seed=0)
    assert list(data["low"]) == [a for a, _ in want.rate] and list(data["high"]) == [b for _, b in want.rate]
    assert np.all(np.asarray(data["low"]) <= np.asarray(data["high"]))
    # the band has its legend entry (the explorer review: it had none), before and after the next edit
    labels = [it.label["value"] for it in ex.speed_tab.figs["legend"].items]
    assert "95 % interval of the growth rate (uncertainty file)" not in labels      # loaded but not yet shown
    ex._load_uncertainty(type("E", (), {"new": path.read_bytes()})())
    ex.edit("trail", "0.07")
    labels = [it.label["value"] for it in ex.speed_tab.figs["legend"].items]
    assert labels[-1] == "95 % interval of the growth rate (uncertainty file)"


def test_a_chair_change_drops_the_old_chairs_results():
    """A result computed for an older chair is never shown (the jobs' generation moved on)."""
    import threading

    from stability.app.jobs import executor
    from stability.app.page import Explorer

    shown: list = []
    gate = threading.Event()
    blocker = executor().submit(gate.wait)      # the worker is busy: the old chair's request waits in the queue
    ex = Explorer(auto_nonlinear=False)
    ex.jobs.submit(lambda: "old chair's result", shown.append, shown.append)
    ex.edit("trail", "0.05")                    # the chair changes: its queued work is dropped
    ex.jobs.submit(lambda: "new chair's result", shown.append, shown.append)
    gate.set()
    blocker.result(timeout=60)
    for f in list(ex.jobs._futures):
        if not f.cancelled():
            f.result(timeout=600)
    assert shown == ["new chair's result"]


HOSTILE_NAMES = ["<script>alert(1)</script>", "<img src=x onerror=alert(2)>", "[x](javascript:alert(3))",
                 "```\n<svg onload=alert(4)>", "</pre><script>alert(5)</script>"]
#: Elements the page's own Markdown and HTML may produce (tables of numbers, emphasis, the command output block).
PAGE_TAGS = {"p", "strong", "em", "b", "i", "br", "table", "thead", "tbody", "tr", "th", "td", "pre", "code", "h2",
             "h3", "ul", "li"}


def _rendered(pane) -> str:
    """What a Markdown or HTML pane sends to the browser (Panel's own transform)."""
    return pane._transform_object(pane.object)["object"]


def _elements(fragment: str) -> tuple[set, list]:
    from html.parser import HTMLParser

    tags: set = set()
    attrs: list = []

    class P(HTMLParser):
        def handle_starttag(self, tag, a):
            tags.add(tag)
            attrs.extend(a)

    P().feed(fragment)
    return tags, attrs


def _show_every_tab(ex) -> None:
    """Write every tab's texts now (a hidden tab's wait until it is shown: stability.app.tabtext)."""
    for texts in ex._texts:
        if texts is not None:
            texts.shown = True
            texts.flush()


def _assert_no_user_markup(ex) -> None:
    import panel as pn

    _show_every_tab(ex)
    from html import unescape

    from panel.models.markup import HTML

    panes = [*ex.layout.select(pn.pane.Markdown), *ex.layout.select(pn.pane.HTML)]
    # the per-edit texts (stability.app.plots.TextBox): Panel's HTML model, whose browser side decodes one level
    divs = [p.object for p in ex.layout.select(pn.pane.Bokeh) if isinstance(p.object, HTML)]
    assert len(panes) > 10 and len(divs) >= 4
    assert all(not d.run_scripts and d.disable_math for d in divs)
    for html in [_rendered(pane) for pane in panes] + [unescape(d.text) for d in divs]:
        tags, attrs = _elements(html)
        assert tags <= PAGE_TAGS, (html, tags - PAGE_TAGS)
        assert all(not k.startswith("on") and "javascript:" not in (v or "") for k, v in attrs), attrs


@pytest.mark.parametrize("name", HOSTILE_NAMES)
def test_hostile_text_from_a_url_a_field_and_files_is_never_markup(name, tmp_path):
    """The explorer review's item 2: a chair name from a shared URL ran script.  Every pane's HTML, as Panel
    renders it for the browser, holds only the page's own elements whatever the user's text."""
    from urllib.parse import urlencode

    from stability.app.page import Explorer

    ex = Explorer(query=urlencode({"chair": "ej-premier", "name": name}), auto_nonlinear=False)
    _show_every_tab(ex)
    assert ex.state.chair.name == name
    assert "alert" in ex.title.text                           # the name is shown (as text)
    _assert_no_user_markup(ex)
    ex.edit("trail", name)                                    # refused: the message quotes the value
    assert ex.state.errors["trail"]
    ex.edit("name", name + " 2")
    ex.state.pin()
    ex._show_compare()
    ex.jobs._futures[-1].result(timeout=300)
    assert ex.compare.text.object.startswith("<pre")
    bad_toml = f'name = "{name}"\nm = "{name}"\n'.replace("\n<", " <").encode()
    ex.state.load_toml(bad_toml, filename=name + ".toml")
    ex.state.load_uncertainty(name.encode(), filename=name)
    ex.apply_fields({"m": name})
    ex.nonlinear.failed(ValueError(name))
    ex.compare.failed(ValueError(name))
    ex.trail.failed(ValueError(name))
    ex.assist.failed(ValueError(name))
    ex.advice.failed(ValueError(name))
    ex._show_messages()
    assert {"trail", "file", "uncertainty", "m"} <= set(ex.state.errors)
    _assert_no_user_markup(ex)


def test_a_chair_whose_modes_share_a_name_does_not_break_the_session():
    """The explorer review's item 1: trail 0.03 m named two branches alike; the legend dropped one and every
    later edit raised IndexError.  Every preset's short trails, then an edit, undo, a preset and the model."""
    from stability.app.page import Explorer
    from stability.app.views import linear_view

    for preset in chair_mod.preset_names():
        ex = Explorer(query=f"chair={preset}", auto_nonlinear=False)
        shared = 0
        for trail in ("0", "0.005", "0.01", "0.02", "0.03", "0.05"):
            assert ex.edit("trail", trail) is None
            names = linear_view(ex.state.chair, ex.state.model).names
            shared += len(names) != len(set(names))
            legend = ex.speed_tab.figs["legend"].items
            assert [it.label["value"].removesuffix(" (below the plot at every speed)") for it in legend] == \
                list(dict.fromkeys(names))
            assert sum(len(it.renderers) for it in legend) == len(names)     # every branch hides with its name
            assert ex._view_errors == {} and ex.state.chair.trail == float(trail)
        assert shared, preset                                  # the case of the review was met
        assert ex.state.undo()
        ex.refresh()
        ex.state.select_preset("revised")
        ex.refresh()
        ex.editor.model.value = "thesis"
        assert ex._view_errors == {} and ex.state.url_query().startswith("chair=revised")


def test_fast_edits_coalesce_and_the_latest_wins():
    """Edits that arrive before the page has drawn are applied in order and drawn once, for the last chair (the
    explorer review: 30 fast edits each computed and sent in full, the views reaching the last one 20 s later)."""
    from stability.app.page import Explorer

    ticks: list = []
    ex = Explorer(deliver=ticks.append, auto_nonlinear=False)        # the document's next tick, run by hand
    drawn: list = []
    refresh = ex.refresh
    ex.refresh = lambda: (drawn.append(ex.state.chair.s1), refresh())
    for value in ("0.30", "0.31", "abc", "0.33"):
        ex.editor.inputs["s1"].value = value                         # as the browser's events arrive
    assert len(ticks) == 1                                           # one drain for all four
    ticks.pop()()
    assert drawn == [0.33] and ex.state.url_query() == "chair=ej-premier&s1=0.33"
    assert ex.state.errors == {}                                     # the bad value was answered by a good one
    assert ex.speed_tab.branch_src.data["real0"] is not None and ex.view.chair.s1 == 0.33
    for want in (0.31, 0.30):                                        # each accepted edit is its own undo step
        assert ex.state.undo() and ex.state.chair.s1 == want


def test_a_hidden_tabs_text_waits_until_the_tab_is_shown():
    import panel as pn

    from stability.app.tabtext import TabText

    pane, texts = pn.pane.Markdown("old"), TabText(shown=False)
    texts.set(pane, "new")
    assert pane.object == "old" and texts.get(pane) == "new"
    texts.set(pane, "newer")                                         # the latest wins
    texts.shown = True
    texts.flush()
    assert pane.object == "newer"
    texts.set(pane, "now")
    assert pane.object == "now"


def test_background_work_runs_for_the_tab_shown_only():
    """An edit starts the Nonlinear or Trail window simulations only while that tab is shown; a tab shown later
    starts its own, once per chair (a hidden tab's runs took both cores from the next edit's answer)."""
    from stability.app.page import TAB_NAMES, Explorer

    ex = Explorer(auto_nonlinear=True)                  # deliver and later at once
    started: list = []
    ex.nonlinear.start = lambda chair, model: started.append(("nonlinear", chair.s1))
    ex.trail.start = lambda chair, model: started.append(("trail", chair.s1))
    ex.edit("s1", "0.31")
    assert started == []                                # the Stability vs speed tab is shown
    ex.tabs.active = TAB_NAMES.index("Nonlinear")
    assert started == [("nonlinear", 0.31)]
    ex.edit("s1", "0.32")                               # shown: the new chair's runs start at once
    assert started[-1] == ("nonlinear", 0.32)
    ex.tabs.active = TAB_NAMES.index("Trail window")
    ex.tabs.active = TAB_NAMES.index("Nonlinear")       # already started for this chair: not again
    assert started[1:] == [("nonlinear", 0.32), ("trail", 0.32)]
