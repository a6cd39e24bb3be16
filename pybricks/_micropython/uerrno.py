"""MicroPython's `uerrno` as EV3 MicroPython has it: the error numbers bricks/ev3dev/mpconfigport.h lists
(MICROPY_PY_UERRNO_LIST), and `errorcode`.  The numbers are this system's, as the OSErrors the simulator
raises carry them (on Linux they are the EV3's)."""

import errno as _errno

_NAMES = (
    "EPERM ENOENT ESRCH EINTR EIO ENXIO E2BIG ENOEXEC EBADF ECHILD EAGAIN ENOMEM EACCES EFAULT ENOTBLK EBUSY "
    "EEXIST EXDEV ENODEV ENOTDIR EISDIR EINVAL ENFILE EMFILE ENOTTY ETXTBSY EFBIG ENOSPC ESPIPE EROFS EMLINK "
    "EPIPE EDOM ERANGE EOPNOTSUPP EAFNOSUPPORT EADDRINUSE ECONNABORTED ECONNRESET ENOBUFS EISCONN ENOTCONN "
    "ETIMEDOUT ECONNREFUSED EHOSTUNREACH EALREADY EINPROGRESS ECANCELED"
).split()

errorcode = {}
for _name in _NAMES:
    if hasattr(_errno, _name):
        globals()[_name] = getattr(_errno, _name)
        errorcode[getattr(_errno, _name)] = _name
del _name
