"""The jail's system-call filter: no new processes, no kernel interfaces an answer has no use for.

bubblewrap loads a classic BPF program (``--seccomp FD``) before it starts
the runner. `program()` builds it for this machine's architecture
(x86-64 or AArch64; elsewhere the jail refuses to start):

- a system call of another ABI (32-bit ``int 0x80`` on x86-64, x32) kills
  the process, so the filter cannot be stepped around;
- ``fork``, ``vfork``, ``clone`` without ``CLONE_THREAD`` fail with EPERM:
  no process can be started, so none can outlive the jail or hold its pipes,
  and a fork bomb ends at once (threads stay possible, inside the limits);
- ``clone3`` fails with ENOSYS, so the C library falls back to ``clone``,
  whose flags the filter can read;
- ``socket`` fails with EPERM for every family but ``AF_UNIX``: no network,
  even where no network namespace can be made;
- namespaces, mounts, ptrace, other processes' memory, BPF, perf, io_uring,
  keyrings, modules and kexec fail with EPERM.

Everything else is allowed: the mount, PID and network namespaces (or the
unprivileged user) and the resource limits do the rest
(``scanviz.exercises.jail``). bubblewrap loads the filter (``--seccomp``);
without bubblewrap the runner loads it itself before the answer runs.
"""

from __future__ import annotations

import errno
import platform
import struct

# BPF instruction classes and fields (linux/filter.h, linux/bpf_common.h)
_LD_W_ABS = 0x20  # BPF_LD | BPF_W | BPF_ABS
_JEQ = 0x15  # BPF_JMP | BPF_JEQ | BPF_K
_JGE = 0x35  # BPF_JMP | BPF_JGE | BPF_K
_JSET = 0x45  # BPF_JMP | BPF_JSET | BPF_K
_RET = 0x06  # BPF_RET | BPF_K
# seccomp return values (linux/seccomp.h)
_ALLOW = 0x7FFF0000
_KILL_PROCESS = 0x80000000
_ERRNO = 0x00050000
# offsets in struct seccomp_data
_NR, _ARCH, _ARG0 = 0, 4, 16
_CLONE_THREAD = 0x00010000
_AF_UNIX = 1
_X32_BIT = 0x40000000

# (audit architecture, {name: number}); generic numbers for AArch64 (asm-generic/unistd.h)
_ARCHITECTURES = {
    "x86_64": (
        0xC000003E,
        {
            "fork": 57, "vfork": 58, "clone": 56, "clone3": 435, "ptrace": 101,
            "process_vm_readv": 310, "process_vm_writev": 311, "unshare": 272, "setns": 308,
            "mount": 165, "umount2": 166, "pivot_root": 155, "chroot": 161, "bpf": 321,
            "perf_event_open": 298, "userfaultfd": 323, "keyctl": 250, "add_key": 248,
            "request_key": 249, "io_uring_setup": 425, "io_uring_enter": 426,
            "io_uring_register": 427, "kexec_load": 246, "kexec_file_load": 320,
            "init_module": 175, "finit_module": 313, "delete_module": 176,
            "open_by_handle_at": 304, "name_to_handle_at": 303, "fsopen": 430, "fsconfig": 431,
            "fsmount": 432, "fspick": 433, "move_mount": 429, "open_tree": 428,
            "mount_setattr": 442, "personality": 135, "socket": 41,
        },
    ),
    "aarch64": (
        0xC00000B7,
        {
            "clone": 220, "clone3": 435, "ptrace": 117, "process_vm_readv": 270,
            "process_vm_writev": 271, "unshare": 97, "setns": 268, "mount": 40, "umount2": 39,
            "pivot_root": 41, "chroot": 51, "bpf": 280, "perf_event_open": 241,
            "userfaultfd": 282, "keyctl": 219, "add_key": 217, "request_key": 218,
            "io_uring_setup": 425, "io_uring_enter": 426, "io_uring_register": 427,
            "kexec_load": 104, "kexec_file_load": 294, "init_module": 105, "finit_module": 273,
            "delete_module": 106, "open_by_handle_at": 265, "name_to_handle_at": 264,
            "fsopen": 430, "fsconfig": 431, "fsmount": 432, "fspick": 433, "move_mount": 429,
            "open_tree": 428, "mount_setattr": 442, "personality": 92, "socket": 198,
        },
    ),
}  # fmt: skip


def supported() -> bool:
    """Whether the filter knows this machine's architecture."""
    return platform.machine() in _ARCHITECTURES


def program(machine: str | None = None) -> bytes:
    """The filter as bubblewrap reads it: an array of ``struct sock_filter`` (8 bytes each)."""
    arch, numbers = _ARCHITECTURES[machine or platform.machine()]
    denied = sorted(n for name, n in numbers.items() if name not in ("clone", "clone3", "socket"))
    # Each entry: (code, jump if true, jump if false, k); jumps are counted in instructions.
    labels: dict[str, int] = {}
    code: list[tuple] = [
        (_LD_W_ABS, 0, 0, _ARCH),
        (_JEQ, 1, 0, arch),
        (_RET, 0, 0, _KILL_PROCESS),
        (_LD_W_ABS, 0, 0, _NR),
    ]
    if machine == "x86_64" or (machine is None and platform.machine() == "x86_64"):
        code.append((_JGE, "kill", None, _X32_BIT))
    code.append((_JEQ, "clone", None, numbers["clone"]))
    code.append((_JEQ, "enosys", None, numbers["clone3"]))
    code.append((_JEQ, "socket", None, numbers["socket"]))
    code.extend((_JEQ, "eperm", None, n) for n in denied)
    code.append((_RET, 0, 0, _ALLOW))
    labels["socket"] = len(code)
    code.append((_LD_W_ABS, 0, 0, _ARG0))  # the address family
    code.append((_JEQ, "allow", "eperm", _AF_UNIX))
    labels["clone"] = len(code)
    code.append((_LD_W_ABS, 0, 0, _ARG0))  # the low 32 bits of the flags (little-endian)
    code.append((_JSET, "allow", "eperm", _CLONE_THREAD))
    labels["eperm"] = len(code)
    code.append((_RET, 0, 0, _ERRNO | errno.EPERM))
    labels["allow"] = len(code)
    code.append((_RET, 0, 0, _ALLOW))
    labels["enosys"] = len(code)
    code.append((_RET, 0, 0, _ERRNO | errno.ENOSYS))
    labels["kill"] = len(code)
    code.append((_RET, 0, 0, _KILL_PROCESS))
    out = bytearray()
    for index, (op, true, false, k) in enumerate(code):
        jt = labels[true] - index - 1 if isinstance(true, str) else true
        jf = labels[false] - index - 1 if isinstance(false, str) else (false or 0)
        out += struct.pack("=HBBI", op, jt, jf, k)
    return bytes(out)
