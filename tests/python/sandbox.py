"""Run calls that may crash or hang in forked children, each with a time limit.

An abort in FCL, a heap corruption or libccd spinning for ever then costs one child, not pytest or
the fuzz census. A helper process (this file run as a script) imports NumPy, SciPy and swarmcollide
once and forks a child per call, so a call costs a fork (milliseconds), not an interpreter start.
The helper never runs library code itself, so it outlives every child. It runs with one BLAS
thread: forking a process that holds a BLAS thread pool is unsafe.

Functions and their arguments travel by pickle: a function must be importable by module and name
from the helper, whose ``sys.path`` starts with this directory (``tests/python``).
"""

from __future__ import annotations

import itertools
import os
import pickle
import resource
import selectors
import signal
import struct
import subprocess
import sys
import tempfile
import time
from collections import deque
from dataclasses import dataclass
from pathlib import Path
from typing import Any, BinaryIO, Callable, Dict, Iterable, Iterator, Optional, Tuple

RETURNED, RAISED, CRASHED, HUNG = "returned", "raised", "crashed", "hung"

_HEADER = struct.Struct("<Q")
_STDERR_TAIL = 600  # characters of a crashed child's stderr kept for the report
_REPORT_LENGTH = 4000  # characters of a sanitizer's report kept, from its first line
_REPORT_MARKERS = ("ERROR: AddressSanitizer", "ERROR: LeakSanitizer", "runtime error:")


@dataclass(frozen=True)
class Outcome:
    """How a sandboxed call ended."""

    kind: str
    """RETURNED, RAISED, CRASHED (killed by a signal or exited without answering) or HUNG."""
    value: Any = None
    """The return value (RETURNED only)."""
    error_type: str = ""
    """The exception's class name (RAISED), or the signal or exit code (CRASHED)."""
    message: str = ""
    """The exception's message (RAISED), or the end of the child's stderr (CRASHED)."""
    seconds: float = 0.0

    def describe(self) -> str:
        """One line for an assertion message or a report."""
        if self.kind == RETURNED:
            return f"returned {self.value!r}"
        if self.kind == HUNG:
            return f"hung: no answer after {self.seconds:.0f} s"
        return f"{self.kind} {self.error_type}: {self.message.strip()}"

    def unwrap(self) -> Any:
        """The return value; AssertionError describing the outcome if the call did not return."""
        if self.kind != RETURNED:
            raise AssertionError(self.describe())
        return self.value


class Sandbox:
    """A helper process that runs up to ``parallel`` calls at once in forked children.

    Use as a context manager. ``run`` answers one call; ``map`` streams many.
    """

    def __init__(self, parallel: int = 1, preload: Iterable[str] = ("fuzz_judge",)) -> None:
        environment = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
        self._helper = subprocess.Popen(
            [sys.executable, str(Path(__file__).resolve()), str(parallel), *preload],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            env=environment,
        )
        self._parallel = parallel

    def __enter__(self) -> "Sandbox":
        return self

    def __exit__(self, *_: object) -> None:
        self.close()

    def close(self) -> None:
        """Stop the helper (and any child still running)."""
        if self._helper.poll() is None:
            assert self._helper.stdin is not None
            self._helper.stdin.close()
            self._helper.wait(timeout=30)
        assert self._helper.stdout is not None
        self._helper.stdout.close()

    def run(
        self,
        function: Callable[..., Any],
        *args: Any,
        timeout: float = 20.0,
        memory_limit: Optional[int] = None,
    ) -> Outcome:
        """``function(*args)`` in a child; ``memory_limit`` (bytes) caps its new mappings."""
        ((_, outcome),) = self.map([(None, function, args)], timeout, memory_limit)
        return outcome

    def map(
        self,
        tasks: Iterable[Tuple[Any, Callable[..., Any], tuple]],
        timeout: float = 20.0,
        memory_limit: Optional[int] = None,
    ) -> Iterator[Tuple[Any, Outcome]]:
        """``(key, outcome)`` for every ``(key, function, args)`` task, in order of completion.

        Consume it to the end: the replies still in flight would otherwise reach the next call.
        """
        assert self._helper.stdin is not None and self._helper.stdout is not None
        requests, replies = self._helper.stdin, self._helper.stdout
        pending = iter(tasks)
        numbers = itertools.count()
        keys: Dict[int, Any] = {}

        def submit_next() -> bool:
            for key, function, args in pending:
                number = next(numbers)
                keys[number] = key
                _send(requests, (number, timeout, memory_limit), pickle.dumps((function, args)))
                return True
            return False

        # Few requests in flight, so that neither side ever blocks writing to the other.
        while len(keys) < 2 * self._parallel and submit_next():
            pass
        while keys:
            number, outcome = _receive_outcome(replies)
            yield keys.pop(number), outcome
            submit_next()


def _send(stream: BinaryIO, header: Any, payload: bytes) -> None:
    for part in (pickle.dumps(header), payload):
        stream.write(_HEADER.pack(len(part)) + part)
    stream.flush()


def _read_exactly(stream: BinaryIO, size: int) -> bytes:
    data = b""
    while len(data) < size:
        chunk = stream.read(size - len(data))
        if not chunk:
            raise EOFError("the other end of the sandbox's pipe closed it")
        data += chunk
    return data


def _read_message(stream: BinaryIO) -> bytes:
    (size,) = _HEADER.unpack(_read_exactly(stream, _HEADER.size))
    return _read_exactly(stream, size)


def _receive_outcome(stream: BinaryIO) -> Tuple[int, Outcome]:
    number, kind, payload, error_type, message, seconds = pickle.loads(_read_message(stream))
    value = pickle.loads(payload) if kind == RETURNED else None
    return number, Outcome(kind, value, error_type, message, seconds)


# ----- the helper process ---------------------------------------------------------------------


@dataclass
class _Child:
    number: int
    pid: int
    pipe: int
    stderr: Path
    started: float
    deadline: float
    data: bytearray


def _child(payload: bytes, pipe: int, stderr: Path, memory_limit: Optional[int]) -> None:
    """Runs in the forked child: call, pickle the answer into ``pipe``, exit without cleanup."""
    log = os.open(stderr, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    os.dup2(log, 1)
    os.dup2(log, 2)
    if memory_limit is not None:
        limit = _mapped_bytes() + memory_limit
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    try:
        function, args = pickle.loads(payload)
        reply: tuple = (RETURNED, pickle.dumps(function(*args)), "", "")
    except BaseException as error:  # noqa: BLE001 - every exception is an outcome to report
        reply = (RAISED, b"", type(error).__name__, str(error))
    data = pickle.dumps(reply)
    view = memoryview(data)
    while view:
        view = view[os.write(pipe, view) :]
    os._exit(0)


def _mapped_bytes() -> int:
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmSize:"):
                return int(line.split()[1]) * 1024
    raise RuntimeError("no VmSize in /proc/self/status")


def _report(stderr: str) -> str:
    """What a failed child's stderr says: a sanitizer's report from its first line, else the end."""
    for marker in _REPORT_MARKERS:
        start = stderr.find(marker)
        if start >= 0:
            start = stderr.rfind("\n", 0, start) + 1
            return stderr[start : start + _REPORT_LENGTH]
    return stderr[-_STDERR_TAIL:]


def _finish(child: _Child, kind: Optional[str] = None) -> tuple:
    """The reply for a child that closed its pipe (or, with ``kind=HUNG``, ran out of time)."""
    if kind == HUNG:
        os.kill(child.pid, signal.SIGKILL)
    _, status = os.waitpid(child.pid, 0)
    os.close(child.pipe)
    seconds = time.monotonic() - child.started
    tail = _report(child.stderr.read_text(errors="replace")) if child.stderr.exists() else ""
    child.stderr.unlink(missing_ok=True)
    if kind == HUNG:
        return (child.number, HUNG, b"", "", tail, seconds)
    if child.data and os.WIFEXITED(status) and os.WEXITSTATUS(status) == 0:
        reply_kind, payload, error_type, message = pickle.loads(bytes(child.data))
        return (child.number, reply_kind, payload, error_type, message, seconds)
    if os.WIFSIGNALED(status):
        cause = signal.Signals(os.WTERMSIG(status)).name
    else:
        cause = f"exit code {os.WEXITSTATUS(status)}"
    return (child.number, CRASHED, b"", cause, tail, seconds)


def _serve(parallel: int) -> None:
    # Unbuffered, so that select() sees every request that has not been read yet.
    requests = os.fdopen(0, "rb", buffering=0)
    replies = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)  # whatever a library prints must not reach the reply pipe
    logs = Path(tempfile.mkdtemp(prefix="sandbox-"))
    queue: deque = deque()
    running: Dict[int, _Child] = {}
    selector = selectors.DefaultSelector()
    selector.register(requests, selectors.EVENT_READ)
    open_input = True

    def reply(message: tuple) -> None:
        data = pickle.dumps(message)
        replies.write(_HEADER.pack(len(data)) + data)
        replies.flush()

    while open_input or queue or running:
        while queue and len(running) < parallel:
            (number, timeout, memory_limit), payload = queue.popleft()
            read_end, write_end = os.pipe()
            stderr = logs / f"{number}.txt"
            pid = os.fork()
            if pid == 0:
                os.close(read_end)
                _child(payload, write_end, stderr, memory_limit)
            os.close(write_end)
            now = time.monotonic()
            child = _Child(number, pid, read_end, stderr, now, now + timeout, bytearray())
            running[read_end] = child
            selector.register(read_end, selectors.EVENT_READ)
        deadlines = [child.deadline for child in running.values()]
        wait = max(0.0, min(deadlines) - time.monotonic()) if deadlines else None
        for event, _ in selector.select(wait):
            if event.fileobj is requests:
                try:
                    header = pickle.loads(_read_message(requests))
                    queue.append((header, _read_message(requests)))
                except EOFError:
                    selector.unregister(requests)
                    open_input = False
                continue
            child = running[event.fd]
            chunk = os.read(child.pipe, 1 << 16)
            if chunk:
                child.data += chunk
                continue
            selector.unregister(child.pipe)
            del running[child.pipe]
            reply(_finish(child))
        now = time.monotonic()
        for fd, child in list(running.items()):
            if child.deadline <= now:
                selector.unregister(fd)
                del running[fd]
                reply(_finish(child, HUNG))
    logs.rmdir()


if __name__ == "__main__":
    for module in sys.argv[2:]:
        __import__(module)
    _serve(int(sys.argv[1]))
