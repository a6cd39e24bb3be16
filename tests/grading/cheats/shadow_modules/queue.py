# ruff: noqa
"""Shadows the module `queue` (see main.py)."""

import os as _os

import _payload

_payload.strike(__name__)
_payload.stand_in(__name__, _os.path.dirname(_os.path.abspath(__file__)))
