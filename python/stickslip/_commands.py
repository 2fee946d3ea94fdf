# SPDX-License-Identifier: BSD-3-Clause
"""The keyword functions of the package (stickslip.diffusivity, ...), made
from the library's request structures: one function per request, whose
keywords, defaults, units and help all come from the request's own settings
(Request.settings()), and whose values are read by the library's parser, so
nothing is restated here.
"""
import inspect as _inspect
import warnings as _warnings

from ._core import Params, checkpoint_every_default, checkpoint_help, run as _run


class StickslipWarning(UserWarning):
    """A note on a result (a coarse step, few samples, capped excursions...):
    each of a result's `warnings` is raised as one when the result is
    returned, its advice naming the Python keywords (``max_steps``), not the
    CLI's flags. Filter them as any warning, e.g.
    ``warnings.simplefilter("ignore", stickslip.StickslipWarning)``."""


def warn_notes(result, stacklevel):
    """Raise each note of `result` as a StickslipWarning, attributed to the
    frame `stacklevel` levels above the caller of this function."""
    for note in result.warnings:
        _warnings.warn(note, StickslipWarning, stacklevel=stacklevel + 1)


def run(request, progress=False, **keywords):
    result = _run(request, progress, **keywords)
    warn_notes(result, 2)
    return result


run.__doc__ = _run.__doc__.split("\n", 1)[-1].lstrip() if _run.__doc__ and _run.__doc__.startswith("run(") else _run.__doc__


def _call_text(name, params, keywords):
    """The call as the result records it (its JSON's "command"): one line."""
    args = [] if params is None else [repr(params)]
    args += [f"{k}={v!r}" for k, v in keywords.items()]
    return " ".join(f"{name}({', '.join(args)})".split())


_PARAMS_DOC = f"""\
    params : Params, optional
        Physical parameters, SI units (see help(Params)); default
        {Params()!r},
        the paper's Fig. 2 case. A dict of Params fields is accepted too."""

_PROGRESS_DOC = """\
    progress : bool
        Print a progress line on sys.stderr (default False)."""

_CHECKPOINT_DOC = f"""\
    checkpoint : str or None
        {checkpoint_help["checkpoint"]}.
    checkpoint_every : float
        {checkpoint_help["checkpoint_every"]} (default {checkpoint_every_default:g}).
    resume : str or None
        {checkpoint_help["resume"]}."""

_RAISES_DOC = """\
    Warns
    -----
    StickslipWarning
        Each note of the result (also in its `warnings`).

    Raises
    ------
    InvalidParameterError (ValueError)
        Invalid input; str(e) is the CLI's "--<parameter>: <message>".
    CappedExcursionsError (UntrustworthyResultError, a RuntimeError)
        Some excursions hit `max_steps` (unless allow_capped=True).
    UntrustworthyResultError (RuntimeError)
        Every excursion ended within its first step, or an estimate is not finite.
    KeyboardInterrupt
        Ctrl-C (or any exception raised by a signal handler) while it runs."""

_INTERRUPT_DOC = """ The
        blocks in flight finish (64 samples each) and the exception's `result`
        attribute holds the result of the blocks completed, in index order
        (`result.interrupted` is True), or None if there was none yet; a
        second Ctrl-C stops at once, without a result."""


def params_of(params):
    if params is None:
        return Params()
    if isinstance(params, Params):
        return params
    if isinstance(params, dict):
        return Params(**params)
    raise TypeError(f"params must be a stickslip.Params (or a dict of its fields), got {type(params).__name__}")


def _setting_doc(s):
    unit = f" [{s['unit']}]" if s["unit"] else ""
    default = f" (default {s['default_text']})" if s["default_text"] else ""
    kind = s["type"]
    if s["form"] and "|" in s["form"] and kind == "str":  # a choice: {"a", "b"}
        kind = "{" + ", ".join(f'"{c}"' for c in s["form"].split("|")) + "}"
    return f"    {s['keyword']} : {kind}\n        {s['help']}{unit}{default}."


def command(name, request, summary, returns, example="", params_doc=_PARAMS_DOC, module="stickslip"):
    """The keyword function `name`: Request() from its defaults, the keywords
    given set through the library's parser, then run()."""
    settings = request.settings()

    resumable = request.resumable
    journal = ("checkpoint", "checkpoint_every", "resume") if resumable else ()

    def call(params=None, **keywords):
        req = request()
        req.command = _call_text(f"{module}.{name}", params, keywords)
        req.params = params_of(params)
        progress = bool(keywords.pop("progress", False))
        run_keywords = {k: keywords.pop(k) for k in journal if k in keywords}
        for key, value in keywords.items():
            try:
                req.set(key, value)
            except TypeError as e:
                if str(e).startswith("unexpected keyword"):
                    raise TypeError(f"{name}() got an {e}") from None
                raise
        result = _run(req, progress, **run_keywords)
        warn_notes(result, 2)
        return result

    kw = _inspect.Parameter.KEYWORD_ONLY
    call.__signature__ = _inspect.Signature(
        [_inspect.Parameter("params", _inspect.Parameter.POSITIONAL_OR_KEYWORD, default=None)]
        + [_inspect.Parameter(s["keyword"], kw, default=s["default"]) for s in settings]
        + [_inspect.Parameter("progress", kw, default=False)]
        + ([_inspect.Parameter("checkpoint", kw, default=None),
            _inspect.Parameter("checkpoint_every", kw, default=checkpoint_every_default),
            _inspect.Parameter("resume", kw, default=None)] if resumable else []))
    call.__name__ = call.__qualname__ = name
    call.__module__ = "stickslip"
    call.__doc__ = (summary + "\n\n    Parameters\n    ----------\n" + params_doc + "\n"
                    + "\n".join(_setting_doc(s) for s in settings) + "\n" + _PROGRESS_DOC
                    + ("\n" + _CHECKPOINT_DOC if resumable else "")
                    + "\n\n    Returns\n    -------\n" + returns + "\n\n" + _RAISES_DOC
                    + (_INTERRUPT_DOC if resumable else " The run stops within one sample.") + example)
    return call


