"""Run a program as a brick would: enter the sandbox, then run the program's source.

    python -I -S -B sandboxed_program.py SETUP_JSON

SETUP: repo (the folder holding ev3sim2d), site_packages (added to sys.path, as the boot does),
scratch (the write path), read (extra read paths), limits (more SandboxPolicy fields), program
(source text), args (given to the program as ARGS) and, if given, seed (random.seed before
entering, as the brick's runtime does).  Prints "REPORT <json>" once inside,
then whatever the program prints.  A program reports each try with attempt(name, action):
one line "RESULT <json>" with ok, and the value or the error.
"""

import json
import sys


def attempt(name, action):
    """Run action(); print whether it worked (its value) or failed (its error)."""
    try:
        value = action()
    except BaseException as err:  # noqa: B036 - a program may raise anything, SystemExit included
        result = {"name": name, "ok": False, "error": f"{type(err).__name__}: {err}"}
    else:
        result = {"name": name, "ok": True, "value": repr(value)[:300]}
    print("RESULT " + json.dumps(result), flush=True)


def main() -> None:
    setup = json.loads(sys.argv[1])
    sys.path.insert(0, setup["repo"])
    sys.path.extend(setup["site_packages"])
    from ev3sim2d.brick import sandbox

    policy = sandbox.SandboxPolicy(
        read_paths=[*setup["read"], *sandbox.default_read_paths()],
        write_paths=[setup["scratch"]],
        keep_fds=[],
        **setup["limits"],
    )
    if "seed" in setup:  # as the brick's runtime seeds the run before it enters the sandbox
        import random

        random.seed(setup["seed"])
    report = sandbox.enter(policy)
    sys.path.remove(setup["repo"])
    print("REPORT " + json.dumps(report), flush=True)
    exec(setup["program"], {"__name__": "__main__", "ARGS": setup["args"], "attempt": attempt})


if __name__ == "__main__":
    main()
