/* Lets a bare-metal Cortex-M build (arm-none-eabi-gcc + newlib) run as a Linux process under
 * user-mode qemu-arm: the program entry and newlib's system layer (_read, _write, _open, ...)
 * implemented with Linux ARM EABI system calls (`svc 0`, number in r7). qemu-arm runs the
 * core-specific Thumb code on its default CPU (user-mode qemu 7.2 aborts for -cpu cortex-m*).
 * Only what a test program needs: stdio on files and the standard streams, a static heap,
 * exit. Not firmware code. Compile it with -fomit-frame-pointer (r7 carries the call number). */
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/stat.h>
#include <sys/types.h>

#undef errno
extern int errno;

int main(int argc, char **argv);
void exit(int status) __attribute__((noreturn));

enum { SYS_EXIT_GROUP = 248, SYS_READ = 3, SYS_WRITE = 4, SYS_OPEN = 5, SYS_CLOSE = 6, SYS_LSEEK = 19, SYS_GETPID = 20 };

static long linux_call(long nr, long a, long b, long c) {
    register long r0 __asm__("r0") = a;
    register long r1 __asm__("r1") = b;
    register long r2 __asm__("r2") = c;
    register long r7 __asm__("r7") = nr;
    __asm__ volatile("svc 0" : "+r"(r0) : "r"(r1), "r"(r2), "r"(r7) : "memory");
    return r0;
}

static int result(long r) {
    if (r < 0 && r > -4096) {
        errno = (int)-r;
        return -1;
    }
    return (int)r;
}

/* The Linux initial stack: argc, argv[0..argc-1], NULL, envp... */
void cross_start(long *sp) __attribute__((noreturn, used));
void cross_start(long *sp) {
    exit(main((int)sp[0], (char **)(sp + 1)));
}

__attribute__((naked, noreturn)) void _start(void) {
    __asm__ volatile("mov r0, sp\n\tbl cross_start\n");
}

void _exit(int status) {
    for (;;) {
        (void)linux_call(SYS_EXIT_GROUP, status, 0, 0);
    }
}

int _read(int fd, char *buf, int len) { return result(linux_call(SYS_READ, fd, (long)buf, len)); }
int _write(int fd, const char *buf, int len) { return result(linux_call(SYS_WRITE, fd, (long)buf, len)); }
int _close(int fd) { return result(linux_call(SYS_CLOSE, fd, 0, 0)); }
int _lseek(int fd, int off, int whence) { return result(linux_call(SYS_LSEEK, fd, off, whence)); }
int _getpid(void) { return result(linux_call(SYS_GETPID, 0, 0, 0)); }
int _kill(int pid, int sig) { (void)pid; (void)sig; errno = EINVAL; return -1; }
int _isatty(int fd) { return fd >= 0 && fd <= 2; }

int _fstat(int fd, struct stat *st) {
    st->st_mode = _isatty(fd) ? S_IFCHR : S_IFREG;
    return 0;
}

/* newlib's open flags → Linux's (they differ beyond the access mode). */
int _open(const char *path, int flags, int mode) {
    long lf = flags & 3;
    if (flags & 0x0008) lf |= 02000;   /* O_APPEND */
    if (flags & 0x0200) lf |= 0100;    /* O_CREAT */
    if (flags & 0x0400) lf |= 01000;   /* O_TRUNC */
    if (flags & 0x0800) lf |= 0200;    /* O_EXCL */
    return result(linux_call(SYS_OPEN, (long)path, lf, mode));
}

static unsigned char heap[4u << 20];
static size_t heap_used;

void *_sbrk(ptrdiff_t incr) {
    void *p = heap + heap_used;
    if (incr < 0 || (size_t)incr > sizeof heap - heap_used) {
        errno = ENOMEM;
        return (void *)-1;
    }
    heap_used += (size_t)incr;
    return p;
}

/* newlib's exit and __libc_init_array may refer to these (no constructors here). */
void _init(void) {}
void _fini(void) {}
