"""The options every command line shares: one parser class, the chair, model, JSON and common options.

:mod:`stability.cli` re-exports these; a command builds its parser from
:class:`OneLineErrorParser` and the ``add_*`` helpers (see docs/architecture.md, "A new command line"), takes
every default from :mod:`stability.settings.defaults`, and :func:`stability.cli.run` adds ``--debug`` and ``--quiet``.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import re
import sys
from collections.abc import Sequence
from typing import Any, NoReturn

from stability import chair as chair_mod
from stability import tires
from stability.cli.numbers import bound_for, number, with_unit
from stability.settings import defaults
from stability.settings.run import RUN_SETTINGS, Setting

__all__ = ["OneLineErrorParser", "add_chair_options", "add_common_options", "add_model_option",
           "add_run_options", "run_from_args", "run_flag", "add_json_options",
           "subparsers", "schema_name", "add_output_option", "check_format", "add_uncertainty_option", "FIGURE_FORMATS"]

_NEGATIVE = re.compile(r"^-(\d|\.\d)")


class OneLineErrorParser(argparse.ArgumentParser):
    """An argument parser whose errors are one line on stderr (exit status 2).

    It also accepts negative numbers as option values (``--speeds -1:1:0.5``,
    ``--cross-slope -2``) and shows plain text in ``--help`` (no reST markup).
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("formatter_class", argparse.RawDescriptionHelpFormatter)
        super().__init__(*args, **kwargs)
        # "-1e308", "-2.5e-3" are numbers, not options (argparse's own pattern misses the exponent)
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")

    def add_argument(self, *args: Any, **kwargs: Any) -> argparse.Action:  # noqa: D102
        # every number is parsed knowing its option's name and plausible range (cli_numbers.OPTION_BOUNDS)
        kind = kwargs.get("type")
        options = [a for a in args if isinstance(a, str) and a.startswith("--")]
        if kind in (float, int) and options:
            kwargs["type"] = number(options[0], kind, bound_for(self.prog, options[0]))
        return super().add_argument(*args, **kwargs)

    def error(self, message: str) -> NoReturn:  # noqa: D102
        # "argument --seed: --seed '-1' is invalid ..." -> "--seed '-1' is invalid ..."
        message = re.sub(r"^argument (--[\w-]+)(?:/-\w)?: (?=\1 )", "", message)
        print(f"error: {message}", file=sys.stderr)
        raise SystemExit(2)

    def format_help(self) -> str:  # noqa: D102
        return super().format_help().replace("``", "")

    def parse_args(self, args: Sequence[str] | None = None, namespace: Any = None) -> Any:  # type: ignore[override]
        """Parse ``args``, joining an option and a following negative number (``--x -1`` -> ``--x=-1``)."""
        argv = list(sys.argv[1:] if args is None else args)
        actions = list(self._actions)
        for a in self._actions:                     # and the options of subcommands
            if isinstance(a, argparse._SubParsersAction):
                actions += [b for sub in a.choices.values() for b in sub._actions]
        takes_value = {s for a in actions if a.option_strings and a.nargs is None and a.const is None
                       for s in a.option_strings}
        out: list[str] = []
        i = 0
        while i < len(argv):
            tok = argv[i]
            if tok in takes_value and i + 1 < len(argv) and _NEGATIVE.match(argv[i + 1]):
                out.append(f"{tok}={argv[i + 1]}")
                i += 2
                continue
            out.append(tok)
            i += 1
        return super().parse_args(out, namespace)


def _fields_epilog() -> str:
    rows = []
    for f in dataclasses.fields(chair_mod.Chair):
        unit = f.metadata["unit"]
        rng = chair_mod.valid_range(f.name) if f.name in chair_mod.LIMITS else ""
        if f.name in ("main_tire", "caster_tire"):
            from stability.tires.registry import names as tire_names

            rng = f"one of {', '.join(tire_names())}, 'linear:<N/deg>' or 'file:<csv>'"
        rows.append(f"  {f.name:22s} {unit:10s} {f.metadata['doc']}" + (f" [{rng}]" if rng else ""))
    return ("chair presets: " + ", ".join(chair_mod.preset_names()) + "\n"
            "settable chair fields (--set NAME=VALUE; unit; meaning [valid range]):\n" + "\n".join(rows))


def add_chair_options(parser: argparse.ArgumentParser, default: str = defaults.CHAIR) -> None:
    """Add ``--chair``, repeatable ``--set NAME=VALUE`` and ``--tire-range``; list the chair fields in ``--help``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser; its epilog gains the list of chair fields.
    default : str, optional
        Value of ``--chair`` when it is not given: a preset name or TOML file
        (default ``"ej-premier"``).
    """
    parser.add_argument("--chair", default=default,
                        help=f"preset name ({', '.join(chair_mod.preset_names())}) or TOML file (default {default})")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="override a chair field (repeatable; fields listed below; a wheel layout: m, i_z, h, "
                             "caster_K_FIELD or wheel_J_FIELD, K and J from 1, SI units)")
    parser.add_argument("--tire-range", choices=tires.RANGE_POLICIES, default=defaults.TIRE_RANGE,
                        help="tire data outside the fitted slip and load range: warn (compute by extrapolation "
                             "and note it in the output; default), clamp (hold the force at the range's edge) "
                             "or raise (refuse)")
    parser.epilog = ((parser.epilog + "\n\n") if parser.epilog else "") + _fields_epilog()


def add_common_options(parser: argparse.ArgumentParser) -> None:
    """Add ``--debug`` (traceback on errors) and ``--quiet`` (no notes, no progress) unless present.

    :func:`run` calls it on a command's parser and on each of its
    subcommands' parsers, so both are accepted before and after a subcommand.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's (or a subcommand's) parser.
    """
    have = {s for a in parser._actions for s in a.option_strings}
    if "--debug" not in have:
        parser.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                            help="show the full traceback on errors")
    if "--quiet" not in have:
        parser.add_argument("--quiet", "-q", action="store_true", default=argparse.SUPPRESS,
                            help="print no notes and no progress on stderr (results and errors only)")


def subparsers(parser: argparse.ArgumentParser) -> list[argparse.ArgumentParser]:
    """The subcommands' parsers of ``parser`` (empty when it has none).

    Parameters
    ----------
    parser : argparse.ArgumentParser

    Returns
    -------
    list of argparse.ArgumentParser
    """
    out: list[argparse.ArgumentParser] = []
    for a in parser._actions:
        if isinstance(a, argparse._SubParsersAction):
            out.extend(dict.fromkeys(a.choices.values()))
    return out


def run_flag(name: str) -> str:
    """The command lines' option of RunSpec field ``name`` (``push_duration`` -> ``--push-duration``).

    Parameters
    ----------
    name : str

    Returns
    -------
    str
    """
    return RUN_SETTINGS[name].flag or "--" + name.replace("_", "-")


def _run_value(flag: str, setting: Setting) -> Any:
    """The argparse ``type`` of one numeric run setting: a finite number within its bound, or a special word."""
    bound = setting.bound
    words = {str(w).lower(): w for w in setting.special}

    def parse(text: str) -> Any:
        if text.strip().lower() in words:
            return words[text.strip().lower()]
        rng = f"; valid range: {setting.range_text('value')}"
        try:
            value = float(text)
        except (TypeError, ValueError, OverflowError):
            value = with_unit(flag, text, setting.unit, rng)
        if value != value or value in (float("inf"), float("-inf")):
            raise argparse.ArgumentTypeError(f"{flag} {text!r} is invalid; expected a finite number{rng}")
        if bound is not None and not bound.holds(value):
            raise argparse.ArgumentTypeError(f"{flag} {text} is invalid{rng}")
        return value

    parse.__name__ = "float"
    return parse


def add_run_options(parser: argparse.ArgumentParser, names: Sequence[str], base: Any = None) -> None:
    """Add the options of the RunSpec fields ``names``, generated from their metadata (one table).

    Each option takes its name, default, valid range or choices and help from
    :data:`stability.settings.run.RUN_SETTINGS`, so a command line refuses
    exactly what the API refuses, with the same range.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    names : sequence of str
        RunSpec fields to offer (e.g. ``("speed", "push_force", "horizon")``).
    base : RunSpec, optional
        The defaults (default ``RunSpec()``).
    """
    from stability.settings.run import RunSpec

    base = base if base is not None else RunSpec()
    for name in names:
        st = RUN_SETTINGS[name]
        flag, default = run_flag(name), getattr(base, name)
        unit = f", {st.unit}" if st.unit else ""
        shown = "none" if default is None else (f"{default:g}" if isinstance(default, float) else str(default))
        if st.choices is not None and set(st.choices) <= {True, False, None}:
            parser.add_argument(flag, dest=name, action=argparse.BooleanOptionalAction, default=default,
                                help=f"{st.help} (default {shown})")
        elif st.choices is not None:
            parser.add_argument(flag, dest=name, choices=list(st.choices), default=default,
                                help=f"{st.help}: {st.range_text(name)} (default {shown})")
        else:
            parser.add_argument(flag, dest=name, type=_run_value(flag, st), default=default,
                                metavar=st.unit.upper().replace("/", "_") or "X",
                                help=f"{st.help}{unit}; {st.range_text('value')} (default {shown})")


def run_from_args(args: argparse.Namespace, names: Sequence[str], base: Any = None, **fixed: Any) -> Any:
    """The RunSpec a command's options describe: ``base`` with the fields ``names`` from ``args``.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options (from :func:`add_run_options`).
    names : sequence of str
        The RunSpec fields the command offers.
    base : RunSpec, optional
        The other fields (default ``RunSpec()``).
    **fixed
        Fields the command sets itself.

    Returns
    -------
    RunSpec

    Raises
    ------
    ValueError
        Settings that do not go together, the message naming the options (``--push-duration``) rather than the
        API's fields.
    """
    from stability.settings.run import RunSpec

    base = base if base is not None else RunSpec()
    try:
        return base.replace(**{n: getattr(args, n) for n in names}, **fixed)
    except ValueError as exc:
        msg = str(exc)
        for n in names:
            msg = re.sub(rf"\b{n}=", f"{run_flag(n)} ", msg)
            msg = re.sub(rf"\b{n}\b(?= =| <| >)", run_flag(n), msg)
        raise ValueError(msg) from None


def add_model_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--model {exact,thesis}`` with the toolkit's default (:data:`stability.settings.defaults.MODEL`).

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    """
    parser.add_argument("--model", default=defaults.MODEL, choices=["exact", "thesis"],
                        help=f"equation variant: exact (the thesis's linearisation corrected) or thesis (program "
                             f"WCHAIR's equations); default {defaults.MODEL}")


def add_json_options(parser: argparse.ArgumentParser) -> None:
    """Add ``--json`` (print JSON to standard output) and ``--json-file FILE`` (write it to a file).

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    """
    name = schema_name(parser.prog)
    where = f"; its JSON Schema: stability/schemas/{name}.json (stability.schemas.schema({name!r}))"
    parser.add_argument("--json", action="store_true",
                        help="print the results as JSON on standard output (an object: keys snake_case with the "
                             f"unit last, arrays over speeds next to speeds_m_s{where})")
    parser.add_argument("--json-file", metavar="FILE",
                        help="write the same JSON to FILE (atomically; with --json too if both are given)")


def schema_name(prog: str) -> str:
    """The JSON Schema name of a command from its parser's ``prog`` (``python -m stability.study critical-impulse``
    -> ``study_critical_impulse``).

    Parameters
    ----------
    prog : str
        The parser's ``prog``.

    Returns
    -------
    str
    """
    words = prog.split()
    tail = words[words.index("-m") + 1:] if "-m" in words else words[1:]
    return "_".join(w.replace("stability.", "").replace("-", "_") for w in tail)


#: Figure formats matplotlib writes from a file suffix; multi-page outputs are PDF only.
FIGURE_FORMATS = ("pdf", "png", "svg")


def add_output_option(parser: argparse.ArgumentParser, formats: Sequence[str], *, what: str,
                      aliases: Sequence[str] = (), required: bool = False, metavar: str = "FILE") -> None:
    """Add ``-o/--output FILE``: the main file a command writes, its format named by the suffix.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    formats : sequence of str
        Suffixes accepted (without the dot), e.g. ``("pdf",)`` for a
        multi-page document or :data:`FIGURE_FORMATS` for one figure; any
        other suffix is refused by :func:`check_format` before any work.
    what : str
        What the file holds, for ``--help`` (e.g. ``"the figures"``).
    aliases : sequence of str, optional
        Former spellings (``--pdf``, ``--plot``) kept as hidden deprecated aliases.
    required : bool, optional
        Whether the command needs it.
    metavar : str, optional
        Name of the value in ``--help``.
    """
    kinds = ", ".join(f".{f}" for f in formats)
    parser.add_argument("-o", "--output", metavar=metavar, required=required, dest="output",
                        help=f"write {what} to FILE; the suffix names the format ({kinds})")
    for alias in aliases:
        parser.add_argument(alias, dest="output", metavar=metavar, help=argparse.SUPPRESS)
    parser.set_defaults(output_formats=tuple(formats))


def check_format(path: str | None, formats: Sequence[str], option: str = "-o") -> str | None:
    """The format of an output ``path`` from its suffix; refuse a suffix not in ``formats``.

    Parameters
    ----------
    path : str or None
        Output file (None: not asked for).
    formats : sequence of str
        Accepted suffixes without the dot.
    option : str, optional
        The option that gave it, for the message.

    Returns
    -------
    str or None
        The format (lower-case suffix), None when ``path`` is None.

    Raises
    ------
    ValueError
        One line naming the option, the file and the accepted suffixes.
    """
    if not path or os.path.isdir(path):       # a directory: check_outputs says so
        return None
    suffix = path.rsplit(".", 1)[-1].lower() if "." in path.rsplit("/", 1)[-1] else ""
    if suffix not in formats:
        raise ValueError(f"{option} {path!r} is invalid; the suffix names the format, valid: "
                         + ", ".join(f".{f}" for f in formats))
    return suffix


def add_uncertainty_option(parser: argparse.ArgumentParser, help: str, *, repeat: bool = False) -> None:
    """Add ``--uncertainty FILE`` (an uncertainty TOML file; repeatable with ``repeat``).

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    help : str
        What the command does with it.
    repeat : bool, optional
        One per chair (``action="append"``).
    """
    if repeat:
        parser.add_argument("--uncertainty", action="append", default=[], metavar="FILE", help=help)
    else:
        parser.add_argument("--uncertainty", metavar="FILE", help=help)


def add_driver_options(parser: argparse.ArgumentParser) -> None:
    """Add ``--reaction-time S``: the driver's effective delay (:class:`stability.driver.Driver`).

    Parameters
    ----------
    parser : argparse.ArgumentParser
    """
    from stability.driver.model import REACTION_TIME_RANGE_S

    lo, hi = REACTION_TIME_RANGE_S
    parser.add_argument("--reaction-time", type=float, metavar="S",
                        help=f"the driver's effective delay in correcting the heading, s ({lo:g} to {hi:g}): print "
                             "the speed up to which this driver can hold the chair straight (default: the chair "
                             "file's [user] reaction_time_s, else not computed)")


def add_intended_speed_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--intended-speed U``: the speed the user wants to drive at, the advisor's limit with a driver.

    Parameters
    ----------
    parser : argparse.ArgumentParser
    """
    parser.add_argument("--intended-speed", type=float, default=None, metavar="U",
                        help="the speed the user wants to drive at, m/s (with --reaction-time or the chair file's "
                             "[user]: a change must keep it within what that driver can hold; default the fastest "
                             "use speed)")


def intended_speed_from_args(args: argparse.Namespace, driver: Any) -> float | None:
    """``--intended-speed`` (parsed within its range, ``OPTION_BOUNDS``), refused in one line without a driver.

    Parameters
    ----------
    args : argparse.Namespace
        With ``intended_speed``.
    driver : stability.driver.Driver or None
        :func:`driver_from_args`.

    Returns
    -------
    float or None
    """
    value = getattr(args, "intended_speed", None)
    if value is not None and driver is None:
        raise ValueError("--intended-speed needs --reaction-time (or a chair file with a [user] table)")
    return value


def driver_from_args(args: argparse.Namespace) -> Any:
    """The driver of ``--reaction-time``, else of the chair file's ``[user]`` table, else None.

    Parameters
    ----------
    args : argparse.Namespace
        With ``reaction_time`` and ``chair``.

    Returns
    -------
    stability.driver.Driver or None
    """
    from stability.chair import user_table
    from stability.driver.model import REACTION_TIME_RANGE_S, Driver

    value = getattr(args, "reaction_time", None)
    if value is not None:
        lo, hi = REACTION_TIME_RANGE_S
        if not (math.isfinite(value) and lo <= value <= hi):
            raise ValueError(f"--reaction-time {value!r} is invalid; valid range: {lo:g} to {hi:g} s")
        return Driver(value, source="--reaction-time")
    table = user_table(args.chair) if getattr(args, "chair", None) else None
    return None if table is None else Driver.from_mapping(table, source=f"{args.chair} [user]")
