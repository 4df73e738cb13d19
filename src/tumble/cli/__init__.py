"""The ``tumble`` command line.

Every error is one line on stderr: exit status 2 for bad input (files, values, options), 1 for a
failure of the computation, never a traceback unless ``--debug`` is given. Heavy modules are
imported inside the commands so that ``tumble --help`` answers at once.
"""

from __future__ import annotations

import errno
import functools
import os
import signal
import sys
import time
import warnings

from ._common import EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from .control import CONTROL_WRITES, SIMULATE_WRITES
from .parser import build_parser

__all__ = ["CONTROL_WRITES", "EXIT_FAILURE", "EXIT_OK", "EXIT_USAGE", "SIMULATE_WRITES", "build_parser", "main"]


class _Terminated(BaseException):
    """Raised by the SIGTERM handler, so that partial output is cleaned up as on Ctrl-C."""


#: The signals the running command received: a subprocess the same Ctrl-C stopped (the demo's ffmpeg) can fail
#: before Python raises KeyboardInterrupt, and its error read "computation failed: CalledProcessError", exit 1.
_signalled: list[int] = []


def _on_sigterm(signum, frame):
    _signalled.append(signum)
    raise _Terminated


def _on_sigint(signum, frame):
    _signalled.append(signum)
    raise KeyboardInterrupt


def _after_signal(exc: BaseException) -> int | None:
    """Exit 130 or 143, said in one line, where ``exc`` came of a signal this run received; else None."""
    if not _signalled:
        return None
    interrupted = _signalled[-1] == signal.SIGINT
    print(f"tumble: {'interrupted' if interrupted else 'terminated'}; nothing written{_kept(exc)}", file=sys.stderr)
    return 130 if interrupted else 143


def _show_warning(fallback, said, message, category, filename, lineno, file=None, line=None) -> None:  # noqa: ANN001
    """``warnings.showwarning`` for the commands: a likely slip of units (:class:`tumble.mass.UnitSlipWarning`:
    a part's or a mesh's density or size no solid has), or one whose class asks for it (``cli_one_line``:
    an unstable control loop), as one line, ``warning: ...``, once a command (``said``: the lines
    already printed; a scenario's inputs are checked before the run checks them again); any other
    warning as ``fallback`` (the one in effect before) shows it."""
    from ..mass import UnitSlipWarning

    if issubclass(category, UnitSlipWarning) or getattr(category, "cli_one_line", False):
        if str(message) not in said:
            said.add(str(message))
            print(f"warning: {message}", file=sys.stderr)
    else:
        fallback(message, category, filename, lineno, file, line)


def _named_files_exist(args) -> None:  # noqa: ANN001
    """Refuse an input file the command line names that does not exist, before the command imports
    what it computes with (numpy, scipy, numba: 0.3-0.6 s), so that a mistyped path is said at once
    (~0.05 s). The inputs are the command's ``inputs`` (its parser's defaults); only a name with a
    suffix is checked here, a file's: a preset (``t-handle``) or a folder is the command's to judge.
    The message is the one reading the file gives (:class:`tumble.validation.NoSuchFileError`)."""
    for name in getattr(args, "inputs", ()):  # an option's ("--body") named in the message, as its other errors are
        value = getattr(args, name.lstrip("-"), None)
        for path in value if isinstance(value, list) else [value]:
            if isinstance(path, str) and os.path.splitext(path)[1] and not os.path.lexists(path):
                from ..validation import NoSuchFileError

                raise NoSuchFileError(f"{name}: {path}: no such file" if name.startswith("--") else f"{path}: no such file")


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``tumble`` console command; returns the exit status.

    0: success; 2: bad input (an ``--out`` or ``--copy`` that cannot be written there among it), or a
    missing optional extra named with its ``pip install`` line (nothing written); 1: a failed
    computation or an I/O failure on the way (disk full: the path is named; nothing half-written); 130 / 143: interrupted
    by SIGINT / SIGTERM (nothing half-written). A reader that closes the pipe early
    (``tumble examples | head -2``) is a normal end: 0, quietly.

    Examples
    --------
    >>> from tumble.cli import EXIT_OK, main
    >>> main(["inertia", "t-handle", "--json"]) == EXIT_OK   # prints the mass properties as JSON
    {...
    True
    >>> main(["simulate", "no-such-file.toml", "--out", "x"])   # bad input: one line on stderr, nothing written
    2
    """
    parser = build_parser()
    argv = sys.argv[1:] if argv is None else list(argv)
    args = parser.parse_args(argv)
    if args.command is None:  # one line on stderr, as every other bad input
        print(f"tumble: error: give a command: {', '.join(_commands(parser))} (tumble --help says what each does)",
              file=sys.stderr)
        return EXIT_USAGE
    args.argv = argv
    started = time.time() - 1.0  # a file system's times may be a second coarse
    if sys.stdout is None:  # started with standard output closed (>&-): the outputs are written, the line goes nowhere
        sys.stdout = open(os.devnull, "w", encoding="utf-8")  # noqa: SIM115 - the process's own, for its lifetime
    stdout = sys.stdout
    sys.stdout = _Stdout(stdout)  # type: ignore[assignment]
    try:
        _signalled.clear()
        previous = signal.signal(signal.SIGTERM, _on_sigterm)
        previous_int = signal.signal(signal.SIGINT, _on_sigint)
    except ValueError:  # not the main thread: leave signals alone
        previous = previous_int = None
    try:
        with warnings.catch_warnings():
            # numeric trouble (overflow, invalid values) becomes a one-line failure, not noise
            warnings.simplefilter("error", RuntimeWarning)
            warnings.showwarning = functools.partial(_show_warning, warnings.showwarning, set())  # restored on exit
            _named_files_exist(args)
            compiled = _compile_seconds()
            status = args.func(args)
            sys.stdout.flush()  # a closed pipe shows here, inside the handlers below, not at exit
            _compile_note(args.command, _compile_seconds() - compiled)
            return status
    except KeyboardInterrupt as exc:
        print(f"tumble: interrupted; nothing written{_kept(exc)}", file=sys.stderr)
        return 130
    except _Terminated as exc:
        print(f"tumble: terminated; nothing written{_kept(exc)}", file=sys.stderr)
        return 143
    except ValueError as exc:
        if args.debug:
            raise
        from ..io.examples import example_hint

        message = _one_line(exc)
        print(f"tumble: error: {message}{example_hint(message)}", file=sys.stderr)
        return EXIT_USAGE
    except ImportError as exc:  # an optional extra is missing: the user's setup, with the hint to install it
        if args.debug:
            raise
        print(f"tumble: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_USAGE
    except OSError as exc:  # the input was fine; writing failed (disk full, permissions)
        if (code := _after_signal(exc)) is not None:
            return code
        if isinstance(exc, BrokenPipeError) and exc.filename is None:
            return _reader_gone()
        if args.debug:
            raise
        if isinstance(exc, _StdoutFailed):  # >/dev/full: the line, not the files, could not be written
            out = getattr(args, "out", None)
            written = out is not None and os.path.exists(out) and os.path.getmtime(out) >= started
            print(f"tumble: failed: standard output: {exc.strerror or _one_line(exc)}"
                  + ("; the outputs were written" if written else f"; nothing written{_kept(exc)}"), file=sys.stderr)
            _reader_gone()
            return EXIT_FAILURE
        refused = _output_refused(args, exc)
        if refused:
            print(f"tumble: error: {refused}; nothing written{_kept(exc)}", file=sys.stderr)
            return EXIT_USAGE
        where = f"{exc.filename}: " if exc.filename else ""
        print(f"tumble: failed: {where}{exc.strerror or _one_line(exc)}; nothing written{_kept(exc)}", file=sys.stderr)
        return EXIT_FAILURE
    except Exception as exc:  # a failure of the computation, not of the input
        if (code := _after_signal(exc)) is not None:
            return code
        if args.debug:
            raise
        print(f"tumble: computation failed: {type(exc).__name__}: {_one_line(exc)}", file=sys.stderr)
        return EXIT_FAILURE
    finally:
        if isinstance(sys.stdout, _Stdout):
            sys.stdout = stdout
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)
            signal.signal(signal.SIGINT, previous_int)


#: A run that waited this long (s) for numba to compile its kernels says so, with the cure.
COMPILE_NOTE_S = 2.0


def _compile_seconds() -> float:
    """:func:`tumble.jit.compile_seconds`, without importing anything where no kernel was made."""
    jit = sys.modules.get("tumble.jit")
    return jit.compile_seconds() if jit is not None else 0.0


def _compile_note(command: str, seconds: float) -> None:
    """At a terminal, say that a command waited ``seconds`` for numba's first compile of its
    kernels and that ``tumble compile`` does it once, ahead (a new user otherwise meets 5-25 s of
    silence and cannot tell it from a slow tool). Not in a pipe or a script: its stderr is theirs."""
    if command != "compile" and seconds >= COMPILE_NOTE_S and sys.stderr.isatty():
        print(f"tumble: this run waited {seconds:.0f} s for numba to compile its kernels, once per install: "
              f"'tumble compile' compiles them all ahead", file=sys.stderr)


class _StdoutFailed(OSError):
    """Standard output could not take the command's line (a full device): its files may be written."""


class _Stdout:
    """Standard output, its write errors (other than a closed pipe) raised as :class:`_StdoutFailed`: an
    OSError names no file, and one of standard output read "nothing written" of a run whose files were."""

    def __init__(self, stream) -> None:  # noqa: ANN001 - any text stream
        self._stream = stream

    def __getattr__(self, name: str):  # noqa: ANN204 - the stream's own
        return getattr(self._stream, name)

    def _guarded(self, call, *args):  # noqa: ANN001, ANN002, ANN202
        try:
            return call(*args)
        except BrokenPipeError:
            raise
        except OSError as exc:
            raise _StdoutFailed(exc.errno, exc.strerror) from exc

    def write(self, text: str) -> int:
        return self._guarded(self._stream.write, text)

    def flush(self) -> None:
        self._guarded(self._stream.flush)


def _commands(parser) -> list[str]:
    """The parser's command names, in the order its help lists them."""
    import argparse

    return next((list(a.choices) for a in parser._actions if isinstance(a, argparse._SubParsersAction)), [])


def _reader_gone() -> int:
    """Standard output's reader closed the pipe (``tumble examples | head -2``): a normal end.

    Standard output is pointed at the null device, so that the interpreter's last flush at exit
    finds nothing to complain about (the recipe of Python's documentation of ``signal``).
    """
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    os.close(devnull)
    return EXIT_OK


#: What creating an output where it cannot be made raises: a place the user named, so bad input (exit 2),
#: not a write that failed on its way (a full disk, exit 1).
_NOT_THERE = frozenset({errno.ENOENT, errno.ENOTDIR, errno.EACCES, errno.EPERM, errno.EROFS})


def _output_refused(args, exc: OSError) -> str:  # noqa: ANN001
    """The line for an output option (``--out``, ``--copy``) naming a place that cannot be written,
    or ``""``: the error's path is that option's value or under it (a sweep's ``DIR.resume``).

    Examples
    --------
    >>> import argparse, errno
    >>> from tumble.cli import _output_refused
    >>> exc = FileNotFoundError(errno.ENOENT, "No such file or directory", "/proc/x.resume")
    >>> _output_refused(argparse.Namespace(out="/proc/x"), exc)
    '--out /proc/x: cannot be written there (No such file or directory: /proc/x.resume); give a place you can write to'
    """
    if exc.errno not in _NOT_THERE or not exc.filename:
        return ""
    for option in ("out", "copy"):
        value = getattr(args, option, None)
        if isinstance(value, str) and value and os.fspath(exc.filename).startswith(value):
            what = exc.strerror if os.fspath(exc.filename) == value else f"{exc.strerror}: {os.fspath(exc.filename)}"
            return f"--{option} {value}: cannot be written there ({what}); give a place you can write to"
    return ""


def _kept(exc: BaseException) -> str:
    """What a failed command left on purpose (a sweep's finished chunks), from the exception's notes."""
    return "".join(f"; {' '.join(note.split())}" for note in getattr(exc, "__notes__", ()))


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
