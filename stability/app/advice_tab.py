"""The explorer's advice tab: the advisor's verdict and recommendation for the current chair, applied in one click.

On request (the advisor simulates every lever: about a minute), on the
background worker: :func:`stability.advise.advise` with the command line's
defaults, shown as :func:`stability.advise.text.advice_text` (what
``python -m stability.advise`` prints).  "Apply" sets the recommended fields
on the chair as one edit (undo takes it back).
"""

from __future__ import annotations

from typing import Any

import panel as pn

from stability.app.markup import literal, pre
from stability.app.state import assignments
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
    """

    def __init__(self, submit: Any, on_change: Any, current: Any, apply: Any) -> None:
        self.submit, self.current, self.apply = submit, current, apply
        self.advice: Any = None
        self.button = pn.widgets.Button(name="advise this chair", button_type="primary", width=180,
                                        css_classes=["run-advice"])
        self.button.on_click(on_change(lambda e: self.start()))
        self.apply_buttons = [pn.widgets.Button(name=name, width=220, disabled=True, css_classes=[css])
                              for name, css in (("apply the recommendation", "apply-1"),
                                                ("apply the runner-up", "apply-2"))]
        for k, b in enumerate(self.apply_buttons):
            b.on_click(on_change(lambda e, k=k: self._apply(k)))
        self.progress = pn.indicators.Progress(active=False, visible=False, width=300, bar_color="primary")
        self.text = pn.pane.Markdown("Press the button: the advisor weighs every lever (trail, axle position, "
                                     "wheelbase, pin friction, caster tire and mass) against shimmy, tipping, "
                                     "turning effort and the cross-slope effort (`python -m stability.advise`, "
                                     "docs/advise.md). It runs simulations: about a minute.",
                                     css_classes=["advice-text"], sizing_mode="stretch_width")
        self.panel = pn.Column(pn.Row(self.button, *self.apply_buttons), self.progress, self.text,
                               sizing_mode="stretch_width")

    def start(self) -> None:
        """Queue the advice for the session's current chair."""
        chair: Chair = self.current()
        self.advice = None
        for b in self.apply_buttons:
            b.disabled = True
        self.progress.visible, self.progress.active = True, True
        self.text.object = f"advising on {literal(chair.name)} (simulating every lever)..."

        def work() -> tuple[Any, str]:
            from stability.advise import advise
            from stability.advise.text import advice_text

            a = advise(chair)
            return a, advice_text(a)

        self.submit(work, self.show, self.failed)

    def failed(self, exc: BaseException) -> None:
        """Show why there is no advice (one line)."""
        self.progress.visible, self.progress.active = False, False
        self.text.object = f"error: could not advise on this chair: {literal(exc)}"

    def show(self, result: tuple[Any, str]) -> None:
        """Show the advice and enable the buttons of the recommendations it makes.

        Parameters
        ----------
        result : (Advice, str)
        """
        self.progress.visible, self.progress.active = False, False
        self.advice, text = result
        recs = list(self.advice.recommendations)
        for k, b in enumerate(self.apply_buttons):
            b.disabled = k >= len(recs)
            if k < len(recs):
                b.name = f"apply: {recs[k].candidate.label}"[:80]
        self.text.object = pre(text)

    def chair_changed(self, chair: Chair) -> None:
        """Disable applying advice given for another chair.

        Parameters
        ----------
        chair : Chair
            The session's chair now.
        """
        if self.advice is not None and self.advice.chair != chair:
            for b in self.apply_buttons:
                b.disabled = True
            if not self.text.object.startswith("*"):
                self.text.object = ("*The chair has changed since this advice: press the button again.*\n\n"
                                    + self.text.object)

    def _apply(self, k: int) -> None:
        recs = list(self.advice.recommendations) if self.advice is not None else []
        if k < len(recs):
            self.apply(assignments(recs[k].candidate.fields))
