# ruff: noqa
"""A harmless helper (as the teacher reads it)."""


def say_hello():
    print("hello from the helper")
