"""Landlock and the other kernel calls the sandbox makes through ctypes (moved here from
app/exercises/sandbox.py, which imports and re-exports them).

The constants of include/uapi/linux/landlock.h, prctl and unshare; `libc()`, the C library;
`landlock_abi()`, the kernel's Landlock ABI version; `landlock_restrict()`, which restricts the
calling process (and what it starts) for good to reading some folders and writing others, with no
TCP (ABI 4+) and signals scoped to itself (ABI 6+). The sandbox's child calls it before its exec
(app/exercises/sandbox.py, `confine`).
"""

from __future__ import annotations

import ctypes
import os
import stat
import sys

# ----- Landlock (include/uapi/linux/landlock.h) ---------------------------------------------------
SYS_CREATE_RULESET, SYS_ADD_RULE, SYS_RESTRICT_SELF = 444, 445, 446   # the same on every arch
CREATE_RULESET_VERSION = 1
RULE_PATH_BENEATH = 1
FS_EXECUTE, FS_WRITE_FILE, FS_READ_FILE, FS_READ_DIR = 1 << 0, 1 << 1, 1 << 2, 1 << 3
FS_REFER, FS_TRUNCATE, FS_IOCTL_DEV = 1 << 13, 1 << 14, 1 << 15
NET_BIND_TCP, NET_CONNECT_TCP = 1 << 0, 1 << 1
SCOPE_ABSTRACT_UNIX_SOCKET, SCOPE_SIGNAL = 1 << 0, 1 << 1
FILE_RIGHTS = FS_EXECUTE | FS_WRITE_FILE | FS_READ_FILE | FS_TRUNCATE | FS_IOCTL_DEV
READ = FS_EXECUTE | FS_READ_FILE | FS_READ_DIR

# ----- prctl, unshare ---------------------------------------------------------------------------
PR_SET_PDEATHSIG, PR_CAPBSET_DROP, PR_SET_CHILD_SUBREAPER, PR_SET_NO_NEW_PRIVS = 1, 24, 36, 38
CLONE_NEWIPC, CLONE_NEWUTS, CLONE_NEWPID, CLONE_NEWNET = 0x08000000, 0x04000000, 0x20000000, \
    0x40000000

_libc = None


def libc():
    global _libc
    if _libc is None:
        _libc = ctypes.CDLL(None, use_errno=True)
        _libc.syscall.restype = ctypes.c_long
    return _libc


def _check(result: int, what: str) -> int:
    if result < 0:
        e = ctypes.get_errno()
        raise OSError(e, f"{what}: {os.strerror(e)}")
    return result


def landlock_abi() -> int:
    """The kernel's Landlock ABI version (0: none: an old kernel, or Landlock not enabled)."""
    if not sys.platform.startswith("linux"):
        return 0
    try:
        r = libc().syscall(SYS_CREATE_RULESET, None, ctypes.c_size_t(0),
                           ctypes.c_uint32(CREATE_RULESET_VERSION))
    except (OSError, AttributeError):
        return 0
    return max(0, int(r))


class _RulesetAttr(ctypes.Structure):
    _fields_ = [("handled_access_fs", ctypes.c_uint64), ("handled_access_net", ctypes.c_uint64),
                ("scoped", ctypes.c_uint64)]


class _PathBeneath(ctypes.Structure):
    _pack_ = 1
    _fields_ = [("allowed_access", ctypes.c_uint64), ("parent_fd", ctypes.c_int32)]


def fs_rights(abi: int) -> int:
    rights = (1 << 13) - 1                      # ABI 1: execute .. make_sym
    if abi >= 2:
        rights |= FS_REFER
    if abi >= 3:
        rights |= FS_TRUNCATE
    if abi >= 5:
        rights |= FS_IOCTL_DEV
    return rights


def landlock_restrict(abi: int, read: list[str], write: list[str]) -> None:
    """Restrict this process (and what it starts) for good: read (and execute) only under
    `read`, read and write only under `write`; no TCP (ABI 4+); signals and abstract unix sockets
    only within (ABI 6+). OSError if the kernel refuses."""
    handled = fs_rights(abi)
    attr = _RulesetAttr(handled, NET_BIND_TCP | NET_CONNECT_TCP if abi >= 4 else 0,
                        SCOPE_SIGNAL | SCOPE_ABSTRACT_UNIX_SOCKET if abi >= 6 else 0)
    size = 24 if abi >= 6 else 16 if abi >= 4 else 8
    lc = libc()
    fd = _check(lc.syscall(SYS_CREATE_RULESET, ctypes.byref(attr), ctypes.c_size_t(size),
                           ctypes.c_uint32(0)), "landlock_create_ruleset")
    try:
        for paths, rights in ((read, READ & handled), (write, handled)):
            for path in paths:
                try:
                    pfd = os.open(path, os.O_PATH | os.O_CLOEXEC)
                except OSError:
                    continue                      # a path this machine lacks
                try:
                    is_dir = stat.S_ISDIR(os.fstat(pfd).st_mode)
                    rule = _PathBeneath(rights if is_dir else rights & FILE_RIGHTS, pfd)
                    _check(lc.syscall(SYS_ADD_RULE, ctypes.c_int(fd),
                                      ctypes.c_int(RULE_PATH_BENEATH), ctypes.byref(rule),
                                      ctypes.c_uint32(0)),
                           f"landlock_add_rule {path}")
                finally:
                    os.close(pfd)
        _check(lc.prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0), "prctl(NO_NEW_PRIVS)")
        _check(lc.syscall(SYS_RESTRICT_SELF, ctypes.c_int(fd), ctypes.c_uint32(0)),
               "landlock_restrict_self")
    finally:
        os.close(fd)
