"""The output directory's lock, as the app takes it (packages/io/src/run_lock.hpp): "<directory>.lock" beside the
directory, held with flock(2) by the one live process that writes or renames it. A script that replaces a run's
directory takes it too, so that it never replaces a directory a run is writing, and no run starts into one it is
replacing.

    with directory_lock(path):   # raises DirectoryInUse naming the holder
        ...replace path...
"""
import contextlib
import fcntl
import os
import socket

SIGNATURE = 'spatula run lock: process '


class DirectoryInUse(RuntimeError):
    pass


@contextlib.contextmanager
def directory_lock(directory):
    path = os.path.abspath(directory).rstrip('/') + '.lock'
    os.makedirs(os.path.dirname(path), exist_ok=True)
    while True:
        descriptor = os.open(path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC | os.O_NOFOLLOW, 0o644)
        holder = os.pread(descriptor, 512, 0).decode(errors='replace').split('\n')[0]
        if holder and not holder.startswith(SIGNATURE):
            os.close(descriptor)
            raise DirectoryInUse(f"'{path}' exists and was not written by spatula: it is never replaced")
        try:
            fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(descriptor)
            raise DirectoryInUse(f"'{directory}' is being written by another run "
                                 f"({holder[len('spatula run lock: '):] or 'another run'}, lock file '{path}')")
        try:   # the file a run that ended removed is not the lock any more: take the one there now
            if os.stat(path).st_ino == os.fstat(descriptor).st_ino:
                break
        except FileNotFoundError:
            pass
        os.close(descriptor)
    try:
        line = f'{SIGNATURE}{os.getpid()} on {socket.gethostname()} (scripts)\n'.encode()
        os.ftruncate(descriptor, 0)
        os.pwrite(descriptor, line, 0)
        yield
    finally:
        os.unlink(path)
        os.close(descriptor)
