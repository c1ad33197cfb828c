# SPDX-License-Identifier: Apache-2.0
"""phasor's exceptions and warnings (raised by the C++ module, defined here so that they carry
plain Python attributes)."""


class Diagnostic:
    """One message about a scene: ``severity`` ("error", "warning"), ``file``, ``line``,
    ``column`` (1-based; 0 when unknown), ``message``, ``text`` (formatted as the command line
    prints it, with the source line and a caret) and ``notes`` (further Diagnostics: where an
    included file was included, where a name was first defined, ...)."""

    __slots__ = ("severity", "file", "line", "column", "message", "text", "notes")

    def __init__(self, severity, file, line, column, message, text, notes=()):
        self.severity = severity
        self.file = file
        self.line = line
        self.column = column
        self.message = message
        self.text = text
        self.notes = list(notes)

    def location(self):
        """``file:line:column`` as the command line writes it (fewer parts when unknown)."""
        if not self.file:
            return "<built-in>"
        if self.line <= 0:
            return self.file
        return f"{self.file}:{self.line}:{self.column}"

    def __str__(self):
        return f"{self.location()}: {self.severity}: {self.message}"

    def __repr__(self):
        return f"Diagnostic({self.severity!r}, {self.location()!r}, {self.message!r})"


class PhasorError(Exception):
    """An error phasor reports about user input (a scene, an image, an argument) with its location
    when it has one: ``file``, ``line``, ``column`` (0 when unknown) and ``message``."""

    def __init__(self, text, file="", line=0, column=0, message=None):
        super().__init__(text)
        self.file = file
        self.line = line
        self.column = column
        self.message = text if message is None else message


class SceneError(PhasorError):
    """A scene that cannot be loaded. ``str(e)`` is what ``phasor check`` prints: every error
    with its source line, then "N errors in 'FILE'". ``errors`` lists the errors as Diagnostics
    (the first 20, as the command line shows them; ``error_count`` is the true number);
    ``file``, ``line``, ``column`` and ``message`` are the first error's."""

    def __init__(self, text, errors, error_count):
        first = errors[0] if errors else Diagnostic("error", "", 0, 0, text, text)
        super().__init__(text, first.file, first.line, first.column, first.message)
        self.errors = list(errors)
        self.error_count = error_count


class RenderError(PhasorError):
    """A render that failed: an integrator refused the scene at render time, or the image would
    not fit in memory."""


class RenderCancelled(KeyboardInterrupt):
    """A render stopped by Ctrl-C (KeyboardInterrupt) — a subclass of KeyboardInterrupt, so an
    ``except KeyboardInterrupt`` catches it. ``image`` is the partial image (each pixel's value and
    variance are those of its own samples; ``image.metadata["phasor:cancelled"] == "true"``), or
    None when the integrator had nothing honest to show (``rs`` needs its whole field). For
    ``render_many`` and ``sweep``, ``images`` lists the finished images and the partial one (None
    for renders that had not started); ``image`` is the partial one."""

    def __init__(self, message, image=None, images=None):
        super().__init__(message)
        self.image = image
        self.images = images if images is not None else ([image] if image is not None else [])


class SceneWarning(UserWarning):
    """A warning about a scene (an unused parameter, a scene without lights, ...): ``diagnostic``
    holds its Diagnostic (file, line, column, message)."""

    def __init__(self, text, diagnostic=None):
        super().__init__(text)
        self.diagnostic = diagnostic


class RenderWarning(UserWarning):
    """A warning found while rendering (a black image and its likely cause, discarded samples,
    render-time events, a render predicted to take very long)."""


class KernelContractError(AssertionError):
    """A Python kernel that fails the kernel contract suite (``phasor.testing.check_kernel``):
    ``report`` holds the whole report."""

    def __init__(self, text, report=None):
        super().__init__(text)
        self.report = report
