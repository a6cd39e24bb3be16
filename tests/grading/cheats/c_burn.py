# ruff: noqa
"""Burn CPU in C: one call that runs for hours inside C code, where the simulator's "you are stuck"
exception (raised between two Python bytecodes) never arrives.

Contained: stopped at the lesson's CPU or wall-clock limit; the other submissions keep their scores
and the class run ends in its usual time plus the limits; this program scores at most what
standing still scores.
"""

import hashlib

MARKER = "EV3CHEAT-c-burn"

hashlib.pbkdf2_hmac("sha512", b"password", b"salt", 10**12)
