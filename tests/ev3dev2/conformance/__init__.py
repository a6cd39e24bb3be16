"""The shim against the real python-ev3dev2 2.1.0: its API (snapshot_api.py) and its writes (record_upstream_writes.py)."""
