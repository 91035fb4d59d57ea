"""The explorer's advice tab weighs the session's user, as ``python -m stability.advise --chair FILE`` does with
the downloaded chair file's ``[user]`` table (before, the tab ignored the user the Tracking tab had measured)."""

from __future__ import annotations

import pytest

pytest.importorskip("panel")

from stability.app.advice_tab import AdviceTab  # noqa: E402
from stability.chair import preset  # noqa: E402


def _tab(user):
    """An advice tab whose jobs run at once, with the advisor replaced by a spy (what it was asked is the test)."""
    seen: dict = {}

    def submit(work, show, failed):
        try:
            show(work())
        except Exception as exc:      # noqa: BLE001 - the tab's own failure path
            failed(exc)

    tab = AdviceTab(submit, lambda f: f, lambda: preset("ej-premier"), lambda texts: None, lambda: user)
    return tab, seen


@pytest.mark.parametrize("user, tau", [(None, None), ({"reaction_time_s": 0.5, "source": "clinic"}, 0.5)])
def test_the_advice_tab_passes_the_sessions_user_to_the_advisor(monkeypatch, user, tau):
    import stability.advise as advise_mod

    tab, seen = _tab(user)

    def spy(chair, **kw):
        seen.update(kw)
        raise ValueError("stop here")          # the tab shows it as its one-line failure

    monkeypatch.setattr(advise_mod, "advise", spy)
    tab.start()
    driver = seen["driver"]
    assert (driver is None) if tau is None else (driver.reaction_time_s == tau and driver.source == "clinic")
    assert "could not advise on this chair: stop here" in tab.texts.get(tab.text)


def test_a_bad_user_table_is_refused_as_the_commands_refuse_it():
    """A table the commands refuse (reaction time out of range) is refused before any work, with their message."""
    tab, _ = _tab({"reaction_time_s": 9.0})
    with pytest.raises(ValueError, match="reaction_time_s"):
        tab.start()


def test_the_explorers_advice_tab_reads_the_user_the_tracking_tab_measured():
    """The page wires the tab to the session: the [user] table the Tracking tab hands over is what it reads."""
    from stability.app.page import Explorer

    ex = Explorer(auto_nonlinear=False)
    assert ex.advice.user() is None
    ex._measured({"reaction_time_s": 0.4})
    assert ex.advice.user() == {"reaction_time_s": 0.4}


def test_the_compare_tab_compares_the_sessions_user_on_every_chair():
    """The Compare tab's table, with the session's user, has the row ``compare --reaction-time`` adds."""
    from stability.app.compare_tab import CompareTab
    from stability.app.page import Explorer

    ex = Explorer(auto_nonlinear=False)
    out: list = []
    tab = CompareTab(lambda work, show, failed: out.append(work()))
    pinned = [preset("revised")]
    tab.show(ex._view(), pinned, "exact", {"reaction_time_s": 0.5})
    assert "speed a user 0.5 s late holds" in out[-1]
    tab.show(ex._view(), pinned, "exact", None)
    assert "s late holds" not in out[-1]


def test_the_page_hands_the_compare_tab_the_sessions_user(monkeypatch):
    from stability.app.page import Explorer

    ex = Explorer(auto_nonlinear=False)
    seen: list = []
    monkeypatch.setattr(ex.compare, "show", lambda v, pinned, model, user=None: seen.append(user))
    ex._measured({"reaction_time_s": 0.4})
    ex._show_compare()
    assert seen[-1] == {"reaction_time_s": 0.4}
