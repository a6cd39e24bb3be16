"""What the motor and drive base tests share: a program prelude that times a call, and the printed lines read
back as {label: [values]}."""

TIMED = """
import time

def timed(label, move):
    start = time.time()
    move()
    print(label, round(time.time() - start, 4))
"""


def output(result) -> dict:
    """{label: [values...]} from the lines the program printed (the run must have finished)."""
    assert result.status == "finished", (result.status, result.reason, result.error)
    return {line.text.split()[0]: line.text.split()[1:] for line in result.trace.output}
