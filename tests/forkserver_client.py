"""The tests' ``rockcli`` command as a client of :mod:`forkserver` (the standard library only, run with ``-I -S``).

``python -I -S forkserver_client.py SOCKET ARG...`` asks the fork server listening on the Unix socket SOCKET to
run ``rockcli ARG...`` as this process would: it sends the arguments, the environment, the working folder, the
umask, the signal mask and the signals ignored here, the process limits and CPU affinity, and its standard input,
output and error (the descriptors themselves, SCM_RIGHTS), and becomes the command: it forwards SIGINT, SIGTERM,
SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2 and SIGALRM to it, and ends as it ended (its exit code, or the signal that
killed it). When this process is killed (SIGKILL), the server kills the command.

When there is no server, or the server declines (an environment or a process setting it was not warmed up
for, see :mod:`forkserver`), the client ``exec``\\ s the real process, exactly what the plain shim runs:
``python -c "import sys; sys.argv[0] = 'rockcli'; from rockcli.cli import run; run()" ARG...``.
"""

import os
import signal
import socket
import struct
import sys

#: What the plain shim runs (``sys.executable`` is the interpreter this client runs on).
REAL = "import sys; sys.argv[0] = 'rockcli'; from rockcli.cli import run; run()"
#: Signals passed on to the command; the others it receives as the process group's or not at all.
FORWARDED = ("SIGINT", "SIGTERM", "SIGHUP", "SIGQUIT", "SIGUSR1", "SIGUSR2", "SIGALRM")
MAGIC = b"RKC1"


def real_process(args):
    """Become the real process (never returns)."""
    os.execv(sys.executable, [sys.executable, "-c", REAL] + list(args))


def _pack(items):
    return b"".join(struct.pack("!I", len(x)) + x for x in items)


def _limits():
    try:
        import resource
    except ImportError:
        return b""
    out = []
    for name in sorted(n for n in dir(resource) if n.startswith("RLIMIT_")):
        try:
            soft, hard = resource.getrlimit(getattr(resource, name))
        except (ValueError, OSError):
            continue
        out.append(f"{name}={soft},{hard}")
    return ";".join(out).encode()


def request(args):
    """The request's payload: a list of byte strings (see :func:`forkserver._parse`)."""
    ignored = [str(int(s)) for s in signal.Signals
               if s not in (signal.SIGKILL, signal.SIGSTOP) and signal.getsignal(s) == signal.SIG_IGN]
    blocked = [str(int(s)) for s in signal.pthread_sigmask(signal.SIG_BLOCK, [])]
    mask = os.umask(0)
    os.umask(mask)
    try:
        cpus = ",".join(str(c) for c in sorted(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        cpus = ""
    fields = [b"%d" % mask, ",".join(ignored).encode(), ",".join(blocked).encode(), cpus.encode(), _limits(),
              b"%d" % os.getpriority(os.PRIO_PROCESS, 0), b"%d" % len(args)]
    fields += [os.fsencode(a) for a in args]
    fields += [k + b"=" + v for k, v in os.environb.items()]
    return fields


def main(argv):
    path, args = argv[1], argv[2:]
    pending, child = [], []

    def forward(signum, frame):
        if child:
            try:
                os.kill(child[0], signum)
            except ProcessLookupError:
                pass
        else:
            pending.append(signum)

    try:
        sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        sock.connect(path)
    except OSError:
        real_process(args)
    fds, open_mask = [], 0
    for fd in (0, 1, 2):
        try:
            os.fstat(fd)
        except OSError:
            continue
        fds.append(fd)
        open_mask |= 1 << fd
    try:
        cwd = os.open(".", os.O_RDONLY | os.O_DIRECTORY)
    except OSError:
        real_process(args)
    payload = _pack(request(args))
    # the handlers go in after the request recorded which signals this process inherited as ignored
    for name in FORWARDED:
        signum = getattr(signal, name)
        if signal.getsignal(signum) != signal.SIG_IGN:
            signal.signal(signum, forward)
    try:
        header = MAGIC + struct.pack("!BI", open_mask, len(payload))
        sock.sendmsg([header], [(socket.SOL_SOCKET, socket.SCM_RIGHTS, struct.pack("%di" % (1 + len(fds)),
                                                                                   cwd, *fds))])
        sock.sendall(payload)
        os.close(cwd)
        reader = sock.makefile("rb")
        first = reader.readline().split()
    except OSError:
        first = []
    if not first or first[0] == b"fallback":
        sock.close()
        for name in FORWARDED:  # what exec keeps: the ignored stay ignored, the others back to the default
            signum = getattr(signal, name)
            if signal.getsignal(signum) == forward:
                signal.signal(signum, signal.SIG_DFL)
        for signum in pending:
            os.kill(os.getpid(), signum)
        real_process(args)
    child.append(int(first[1]))
    for signum in pending:
        forward(signum, None)
    try:
        last = reader.readline().split()
    except OSError:
        last = []
    if len(last) == 2 and last[0] == b"exit":
        os._exit(int(last[1]))
    if len(last) == 2 and last[0] == b"signal":
        signum = int(last[1])
        signal.signal(signum, signal.SIG_DFL)
        signal.pthread_sigmask(signal.SIG_UNBLOCK, [signum])
        os.kill(os.getpid(), signum)
        os._exit(128 + signum)
    os.write(2, b"rockcli (tests' fork server client): the server went away before the command ended\n")
    os._exit(70)


if __name__ == "__main__":
    main(sys.argv)
