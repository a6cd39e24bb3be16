"""
A folder tree standing in for /sys/class, served to the ev3dev2 shim as an ``ev3dev2._link`` backend.

python-ev3dev2's own tests (its tests/api_tests.py, which upstream_suite.py runs) use
ev3dev-lang-fake-sys: a folder that copies the layout of /sys/class
(``<root>/<class>/<device>/<attribute>``, e.g. ``tacho-motor/motor0/speed_sp``), each
attribute a small file holding its value.  The real
library opens those files; our shim asks ``_link`` instead, so ``FakeSysfs`` reads and writes
the same files on its behalf, as a sysfs would:

- devices are the folders of ``<root>/<class>``, matched by name pattern and attribute values
  as python-ev3dev2's ``list_device_names`` matches them (a value *contains* the wanted text);
- a read gives the file's text; a missing attribute (or device) is ENOENT, as on the brick;
- a write replaces the value, which then reads back with a newline after it, as a sysfs
  attribute shows it; a write cannot create an attribute (ENOENT);
- there are no drivers behind the files: writing ``command`` stores the command, which reads
  back and moves nothing (fake-sys's behaviour, which api_tests.py's joystick test reads
  back), and nothing range-checks a value;
- ``poll`` returns at once, as select.poll does on a regular file;
- brick features that are not sysfs attributes (sound, buttons, the LCD) are not there.

The root is ``ev3dev2.Device.DEVICE_ROOT_PATH`` at the moment of each access unless one is
given: upstream's tests point that class attribute at their arena, as python-ev3dev2 2.1.0
finds its devices under it (``Device.__init__``: ``abspath(Device.DEVICE_ROOT_PATH + '/' +
class_name)``).
"""

import errno
import fnmatch
import os


class FakeSysfs:
    """An ``ev3dev2._link`` backend whose devices are folders of attribute files."""

    def __init__(self, root=None):
        self._root = root

    @property
    def root(self) -> str:
        if self._root is not None:
            return self._root
        import ev3dev2

        return ev3dev2.Device.DEVICE_ROOT_PATH

    def _path(self, class_name, device_name, attribute=None):
        parts = [self.root, class_name, device_name] + ([attribute] if attribute else [])
        return os.path.join(*parts)

    # -- the backend interface ----------------------------------------------
    def list_device_names(self, class_name, name_pattern, match):
        folder = os.path.join(self.root, class_name)
        if not os.path.isdir(folder):
            return []
        return [
            name
            for name in sorted(os.listdir(folder))
            if fnmatch.fnmatch(name, name_pattern)
            and all(self._matches(class_name, name, key, pattern) for key, pattern in match.items())
        ]

    def _matches(self, class_name, device_name, attribute, pattern):
        try:
            value = self.read(class_name, device_name, attribute).strip()
        except OSError:
            return False
        if isinstance(pattern, list):
            return any(value.find(p) >= 0 for p in pattern)
        return value.find(pattern) >= 0

    def read(self, class_name, device_name, attribute):
        with open(self._path(class_name, device_name, attribute), "rb") as file:
            return file.read().decode("latin-1")

    def write(self, class_name, device_name, attribute, value):
        if isinstance(value, str):
            value = value.encode("latin-1")
        path = self._path(class_name, device_name, attribute)
        if not os.path.isfile(path):
            raise OSError(errno.ENOENT, "No such file or directory", path)
        with open(path, "wb") as file:
            file.write(bytes(value) if bytes(value).endswith(b"\n") else bytes(value) + b"\n")

    def poll(self, class_name, device_name, attribute, timeout_ms):
        """A regular file is always ready: nothing to wait for."""

    def call(self, feature, *args):
        raise NotImplementedError(f"a fake sysfs has only device attributes, no {feature!r}")
