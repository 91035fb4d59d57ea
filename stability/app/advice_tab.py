"""The explorer's advice tab: the advisor's verdict and recommendation for the current chair, applied in one click.

On request (the advisor simulates every lever: several seconds), on the
background worker: :func:`stability.advise.advise` with the command line's
defaults and the session's user (the Tracking tab's or the uploaded chair
file's ``[user]`` table, as ``python -m stability.advise --chair FILE`` reads
it), shown as :func:`stability.advise.text.advice_text` (what
``python -m stability.advise`` prints).  "Apply" sets the recommended fields
on the chair as one edit (undo takes it back).
"""

from __future__ import annotations

import warnings
from typing import Any

import panel as pn

from stability.app.editor import BUTTON_WRAP
from stability.app.edits import assignments
from stability.app.markup import PRE_STYLESHEET, literal, pre
from stability.app.measures import warning_lines
from stability.app.nonlinear_tab import FRESH, STALE, busy_bar, show_busy
from stability.app.tabtext import TabText
from stability.app.widgets import widget
from stability.chair import Chair

__all__ = ["AdviceTab"]


class AdviceTab:
    """The advice tab of one session.

    Parameters
    ----------
    submit : callable
        ``submit(work, show, failed)`` of the session's :class:`~stability.app.jobs.Jobs`.
    on_change : callable
        Wraps a widget callback as the page does.
    current : callable
        ``current() -> Chair``: the session's chair now.
    apply : callable
        ``apply(texts) -> message or None``: sets fields on the session's chair (one edit) and redraws.
    user : callable, optional
        ``user() -> dict or None``: the session's ``[user]`` table; the advice weighs the speed that driver can
        hold (:func:`stability.advise.advise`'s ``driver``), as the commands do with the downloaded chair file.
    """

    def __init__(self, submit: Any, on_change: Any, current: Any, apply: Any, user: Any = None) -> None:
        self.submit, self.current, self.apply = submit, current, apply
        self.user = user if user is not None else (lambda: None)
        self.advice: Any = None
        self.button = widget(pn.widgets.Button, "advise this chair", kind="primary", width=260,
                                        stylesheets=BUTTON_WRAP,
                                        css_classes=["run-advice"])
        self.button.on_click(on_change(lambda e: self.start()))
        self.apply_buttons = [widget(pn.widgets.Button, name, disabled=True, css_classes=[css], kind=kind,
                                                sizing_mode="stretch_width", stylesheets=BUTTON_WRAP)
                              for name, css, kind in (("apply the recommendation", "apply-1", "success"),
                                                      ("apply the runner-up", "apply-2", "default"))]
        for k, b in enumerate(self.apply_buttons):
            b.on_click(on_change(lambda e, k=k: self._apply(k)))
        self.progress = busy_bar()
        self.texts = TabText()
        self.text = pn.pane.Markdown("Press the button: the advisor weighs every lever (trail, axle position, "
                                     "wheelbase, pin friction, caster tire and mass) against shimmy, tipping, "
                                     "turning effort, the cross-slope effort and, once the Tracking tab or an "
                                     "uploaded chair file's [user] gives the user, the speed that user can hold "
                                     "(`python -m stability.advise`, "
                                     "docs/advise.md). It runs simulations: several seconds.",
                                     css_classes=["advice-text"], sizing_mode="stretch_width",
                                     stylesheets=[PRE_STYLESHEET])
        self.panel = pn.Column(self.button, self.progress, *self.apply_buttons, self.text,
                               sizing_mode="stretch_width")

    def start(self) -> None:
        """Queue the advice for the session's current chair."""
        chair: Chair = self.current()
        table = self.user()
        from stability.driver import Driver

        driver = None if not table else Driver.from_mapping(table, source="the session's [user]")
        self.button.name = "advise this chair"
        self.advice = None
        for b in self.apply_buttons:
            b.disabled = True
        show_busy(self.progress, True)
        self.text.styles = FRESH
        who = "" if driver is None else f" for a user {driver.reaction_time_s:g} s late"
        self.texts.set(self.text, f"advising on {literal(chair.name)}{who} (simulating every lever)...")

        def work() -> tuple[Any, str]:
            from stability.advise import advise
            from stability.advise.text import advice_text

            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                a = advise(chair, driver=driver)
            return a, advice_text(a) + "".join(f"\nnote: {line}" for line in warning_lines(caught))

        self.submit(work, self.show, self.failed)

    def failed(self, exc: BaseException) -> None:
        """Show why there is no advice (one line)."""
        show_busy(self.progress, False)
        self.texts.set(self.text, f"error: could not advise on this chair: {literal(exc)}")

    def show(self, result: tuple[Any, str]) -> None:
        """Show the advice and enable the buttons of the recommendations it makes.

        Parameters
        ----------
        result : (Advice, str)
        """
        show_busy(self.progress, False)
        self.advice, text = result
        recs = list(self.advice.recommendations)
        for k, b in enumerate(self.apply_buttons):
            what = ("apply the recommendation", "apply the runner-up")[k]
            b.disabled = k >= len(recs)
            b.name = f"{what}: {recs[k].candidate.label}" if k < len(recs) else what
        self.text.styles = FRESH
        self.texts.set(self.text, pre(text))

    def chair_changed(self, chair: Chair) -> None:
        """Disable applying advice given for another chair.

        Parameters
        ----------
        chair : Chair
            The session's chair now.
        """
        if self.advice is None:
            return
        same = self.advice.chair == chair
        for k, b in enumerate(self.apply_buttons):
            b.disabled = not same or k >= len(self.advice.recommendations)
        self.text.styles = FRESH if same else STALE
        self.button.name = "advise this chair" if same else "advise the changed chair (this advice is for another)"

    def _apply(self, k: int) -> None:
        recs = list(self.advice.recommendations) if self.advice is not None else []
        if k < len(recs):
            self.apply(assignments(recs[k].candidate.fields))
