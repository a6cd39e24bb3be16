"""The debugger for an editor: a Debug Adapter Protocol server on 127.0.0.1 (`ev3sim2d run --debug-adapter`).

VS Code attaches to it with the Python extension's debugpy configuration (`"request": "attach",
"connect": {"host": "127.0.0.1", "port": ...}`), as `ev3sim2d init vscode` writes it.  It accepts one
connection, before the run starts, and closes after the session.  Nobody else on the computer can
attach: the attach request must carry the server's token (`ev3sim2dToken`, compared in constant time),
which the launch configuration passes; a wrong one is refused and the connection closed.

It is the same front end as the terminal's prompt (debug_prompt.py), spoken in DAP: the program stops
at its first line (brick/debugger.py, "start"), the adapter gives it the breakpoints the editor set and
lets it go on (unless the editor asked to stop on entry); at each stop it tells the editor (`stopped`)
and answers its requests (threads, stackTrace, scopes, variables, evaluate, setBreakpoints) with the
brick's events, until a request lets the program go on (continue, next, stepIn, stepOut).  While it is
stopped the whole world waits.  Breakpoints set while the program runs take effect at its next stop.
"""

from __future__ import annotations

import hmac
import json
import os
import secrets
import socket
import sys

from ..simulator.run import shown_file
from .debug_prompt import brick_file

HEADER_LIMIT = 1024
MESSAGE_LIMIT = 1 << 20  # bytes of a request, at most
RESUME = {"continue": "continue", "next": "next", "stepIn": "step", "stepOut": "return"}
LOCALS, GLOBALS = 1, 2  # variablesReference of the top frame's two scopes


class DebugAdapter:
    """The front end: run_programs' debugger(robot index, shown, real, event) -> command, over DAP."""

    def __init__(self, port: int = 0, token: str | None = None, announce=None) -> None:
        self.token = token or secrets.token_urlsafe(16)
        self.server = socket.create_server(("127.0.0.1", port))
        self.port = self.server.getsockname()[1]
        self.announce = announce or (lambda text: print(text, file=sys.stderr, flush=True))
        self.client: socket.socket | None = None
        self.buffer = b""
        self.seq = 0
        self.breakpoints: dict[str, list[int]] = {}  # file (as the editor names it) -> lines
        self.stop_on_entry = False
        self.queue: list[dict] | None = None  # commands the brick gets one after the other (breakpoints)
        self.then: dict | None = None  # after them: the stop to show (None: the program goes on)
        self.waiting: dict | None = None  # the editor's request the brick's next event answers
        self.started = False  # the first stop (the program's first line) is the adapter's own
        self.stopped: dict | None = None  # the stop the editor is looking at
        self.thread_ids: dict[str, int] = {"MainThread": 1}
        self.thread_names: dict[int, str] = {1: "MainThread"}

    # ------------------------------------------------------------ the session's start
    def attach(self, timeout_s: float | None = None) -> bool:
        """Wait for the editor, and its requests up to configurationDone; False if it never came right."""
        self.announce(f"ev3sim2d: waiting for the debugger on 127.0.0.1:{self.port} (token {self.token})")
        self.server.settimeout(timeout_s)
        try:
            self.client, _ = self.server.accept()
        except OSError:
            return False
        finally:
            self.server.close()
        self.client.settimeout(None)
        attached = False
        while True:
            request = self._receive()
            if request is None:
                return False
            command = request.get("command")
            if command == "initialize":
                self._respond(
                    request,
                    body={"supportsConfigurationDoneRequest": True, "supportsEvaluateForHovers": True},
                )
            elif command in ("attach", "launch"):
                arguments = request.get("arguments") or {}
                given = str(arguments.get("ev3sim2dToken", ""))
                if not hmac.compare_digest(given.encode(), self.token.encode()):
                    self._respond(
                        request, success=False, message="this is not your run: the token does not match"
                    )
                    self.close()
                    return False
                self.stop_on_entry = arguments.get("stopOnEntry") is True
                attached = True
                self._respond(request)
                self._event("initialized")
            elif command == "setBreakpoints":
                self._set_breakpoints(request)
            elif command == "setExceptionBreakpoints":
                self._respond(request, body={"breakpoints": []})
            elif command == "configurationDone":
                self._respond(request)
                if attached:
                    return True
            elif command == "disconnect":
                self._respond(request)
                self.close()
                return False
            else:
                self._respond(
                    request, success=False, message=f"{str(command)[:50]} is not supported before attach"
                )

    # ------------------------------------------------------------ while the program runs
    def __call__(self, index: int, shown: str, real: str, event: dict) -> dict:
        if self.client is None:  # (no editor, or it went away: the program runs on)
            return {"cmd": "continue"}
        if not self.started:  # the program's first line: it gets the breakpoints, then goes on
            self.started = True
            self._queue(self._break_commands(shown, real), stop=event if self.stop_on_entry else None)
            return self._next(shown, real)
        if self.queue is not None:  # (the brick answered a queued command: the next one)
            return self._next(shown, real)
        if self.waiting is not None:
            self._answer(self.waiting, event, shown, real)
            self.waiting = None
            return self._serve(shown, real)
        if event.get("event") == "stopped":
            self._show_stop(event)
            return self._serve(shown, real)
        return {"cmd": "continue"}

    def _queue(self, commands: list[dict], stop: dict | None) -> None:
        """Commands to give the brick one after the other; then show the stop (or let the program go on)."""
        self.queue, self.then = list(commands), stop

    def _next(self, shown: str, real: str) -> dict:
        if self.queue:
            return self.queue.pop(0)
        self.queue, stop, self.then = None, self.then, None
        if stop is None:
            return {"cmd": "continue"}
        if stop is not self.stopped:
            self._show_stop(stop, entry=True)
        return self._serve(shown, real)

    def _show_stop(self, event: dict, entry: bool = False) -> None:
        self.stopped = event
        reason = "entry" if entry else event.get("reason", "step")
        body = {
            "reason": reason,
            "threadId": self._thread_id(event.get("thread", "")),
            "allThreadsStopped": True,
        }
        self._event("stopped", body)

    def _break_commands(self, shown: str, real: str) -> list[dict]:
        return [
            {"cmd": "break", "file": brick_file(file, shown, real), "line": line}
            for file, lines in self.breakpoints.items()
            for line in lines
        ]

    def _serve(self, shown: str, real: str) -> dict:
        """Answer the editor's requests while the program is stopped, until one needs the brick."""
        while True:
            request = self._receive()
            if request is None:  # the editor went away: the program goes on, and nothing stops it again
                self.client = None
                return {"cmd": "clear"} if self.breakpoints else {"cmd": "continue"}
            command = request.get("command")
            arguments = request.get("arguments") or {}
            if command in RESUME:
                self._respond(request, body={"allThreadsContinued": True} if command == "continue" else None)
                self.stopped = None
                return {"cmd": RESUME[command]}
            if command == "threads":
                names = (self.stopped or {}).get("threads") or ["MainThread"]
                threads = [{"id": self._thread_id(n), "name": n} for n in names]
                self._respond(request, body={"threads": threads})
            elif command in ("stackTrace", "evaluate", "variables"):
                self.waiting = request
                if command == "stackTrace":
                    return {"cmd": "where", "thread": self.thread_names.get(arguments.get("threadId"))}
                if command == "evaluate":
                    return {"cmd": "eval", "expr": str(arguments.get("expression", ""))}
                reference = arguments.get("variablesReference")
                return {"cmd": "variables", "scope": "globals" if reference == GLOBALS else "locals"}
            elif command == "scopes":
                scopes = [
                    {"name": "Locals", "variablesReference": LOCALS, "expensive": False},
                    {"name": "Globals", "variablesReference": GLOBALS, "expensive": False},
                ]
                self._respond(request, body={"scopes": scopes})
            elif command == "setBreakpoints":
                self._set_breakpoints(request)
                self._queue([{"cmd": "clear"}, *self._break_commands(shown, real)], stop=self.stopped)
                return self._next(shown, real)
            elif command == "disconnect":
                self._respond(request)
                self.close()
                return {"cmd": "clear"}
            elif command == "pause":
                self._respond(request)  # (it is stopped already)
            else:
                self._respond(request, success=False, message=f"{str(command)[:50]} is not supported")

    def _answer(self, request: dict, event: dict, shown: str, real: str) -> None:
        """Answer the editor's request with the brick's event."""
        command = request.get("command")
        if event.get("event") == "error":
            self._respond(
                request, success=False, message=event.get("message", "the debugger could not do that")
            )
        elif command == "stackTrace":
            frames = event.get("frames", [])[::-1]  # (the brick gives them outermost first)
            body = [
                {
                    "id": number + 1,
                    "name": frame["function"],
                    "line": frame["line"],
                    "column": 1,
                    "source": {"path": os.path.abspath(shown_file(frame["file"], shown, real))},
                }
                for number, frame in enumerate(frames)
            ]
            self._respond(request, body={"stackFrames": body, "totalFrames": len(body)})
        elif command == "evaluate":
            self._respond(
                request,
                success=not event.get("error"),
                body={"result": event.get("text", ""), "variablesReference": 0},
                message=event.get("text") if event.get("error") else None,
            )
        elif command == "variables":
            variables = [
                {"name": v["name"], "value": v["value"], "type": v["type"], "variablesReference": 0}
                for v in event.get("variables", [])
            ]
            self._respond(request, body={"variables": variables})

    def finished(self, exit_code: int) -> None:
        """The run is over: tell the editor, and close."""
        if self.client is not None:
            self._event("exited", {"exitCode": exit_code})
            self._event("terminated")
        self.close()

    def close(self) -> None:
        if self.client is not None:
            try:
                self.client.close()
            finally:
                self.client = None
        self.server.close()

    # ------------------------------------------------------------ breakpoints
    def _set_breakpoints(self, request: dict) -> None:
        arguments = request.get("arguments") or {}
        path = str((arguments.get("source") or {}).get("path", ""))
        lines = [b.get("line") for b in arguments.get("breakpoints") or [] if type(b.get("line")) is int]
        self.breakpoints[path] = lines[:64]
        if not self.breakpoints[path]:
            del self.breakpoints[path]
        verified = [{"verified": True, "line": line} for line in lines[:64]]
        self._respond(request, body={"breakpoints": verified})

    def _thread_id(self, name: str) -> int:
        """A thread's id for the editor: the same for the same name all session long."""
        if name not in self.thread_ids:
            self.thread_ids[name] = len(self.thread_ids) + 1
            self.thread_names[self.thread_ids[name]] = name
        return self.thread_ids[name]

    # ------------------------------------------------------------ the wire
    def _receive(self) -> dict | None:
        """The editor's next request; None once it is gone (or sends what is not DAP)."""
        while b"\r\n\r\n" not in self.buffer:
            if len(self.buffer) > HEADER_LIMIT or not self._read():
                return None
        header, self.buffer = self.buffer.split(b"\r\n\r\n", 1)
        length = None
        for line in header.split(b"\r\n"):
            name, _, value = line.partition(b":")
            if name.strip().lower() == b"content-length" and value.strip().isdigit():
                length = int(value)
        if length is None or length > MESSAGE_LIMIT:
            return None
        while len(self.buffer) < length:
            if not self._read():
                return None
        body, self.buffer = self.buffer[:length], self.buffer[length:]
        try:
            message = json.loads(body)
        except ValueError:
            return None
        return message if type(message) is dict and message.get("type") == "request" else None

    def _read(self) -> bool:
        try:
            chunk = self.client.recv(65536) if self.client is not None else b""
        except OSError:
            return False
        self.buffer += chunk
        return bool(chunk)

    def _send(self, message: dict) -> None:
        self.seq += 1
        data = json.dumps({"seq": self.seq, **message}).encode()
        try:
            self.client.sendall(b"Content-Length: %d\r\n\r\n" % len(data) + data)
        except (OSError, AttributeError):
            self.client = None

    def _respond(
        self, request: dict, success: bool = True, body: dict | None = None, message: str | None = None
    ) -> None:
        response = {
            "type": "response",
            "request_seq": request.get("seq", 0),
            "command": request.get("command"),
            "success": success,
        }
        if body is not None:
            response["body"] = body
        if message is not None:
            response["message"] = message
        self._send(response)

    def _event(self, name: str, body: dict | None = None) -> None:
        self._send({"type": "event", "event": name, **({"body": body} if body is not None else {})})
