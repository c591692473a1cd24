/* An instruction counter for qemu-user's TCG plugin interface (QEMU 7.2, plugin API
 * version 1), for bench/neon/steps.sh. Debian's qemu-user runs plugins (-plugin) but ships
 * none, nor qemu-plugin.h, so the few declarations it needs are written out here.
 *
 * It counts every executed guest instruction (inline, per translation block) and, at each
 * clock_gettime system call, writes the running count as one line to the file named by
 * the plugin argument `out=PATH` (stderr without it). A program that reads the clock before
 * and after each step (folio-bench's play_in does) thus gives the instructions of every
 * step as the differences of consecutive line pairs. The total goes to stderr at exit.
 *
 * Build: gcc -O2 -shared -fPIC -o libinsn.so bench/neon/insn.c
 * Use:   qemu-aarch64 -L /usr/aarch64-linux-gnu -plugin ./libinsn.so,out=counts.txt PROGRAM */
#include <inttypes.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

typedef uint64_t qemu_plugin_id_t;
struct qemu_plugin_tb;
typedef struct qemu_info_t qemu_info_t;
enum qemu_plugin_op { QEMU_PLUGIN_INLINE_ADD_U64 };
typedef void (*tb_trans_cb)(qemu_plugin_id_t, struct qemu_plugin_tb *);
typedef void (*udata_cb)(qemu_plugin_id_t, void *);
typedef void (*syscall_cb)(qemu_plugin_id_t, unsigned int, int64_t, uint64_t, uint64_t,
                           uint64_t, uint64_t, uint64_t, uint64_t, uint64_t, uint64_t);
void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t, tb_trans_cb);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *);
void qemu_plugin_register_vcpu_tb_exec_inline(struct qemu_plugin_tb *, enum qemu_plugin_op,
                                              void *, uint64_t);
void qemu_plugin_register_vcpu_syscall_cb(qemu_plugin_id_t, syscall_cb);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t, udata_cb, void *);

__attribute__((visibility("default"))) int qemu_plugin_version = 1;

/* aarch64 Linux's clock_gettime. */
#define SYS_CLOCK_GETTIME 113

static uint64_t insns;
static FILE *out;

static void translated(qemu_plugin_id_t id, struct qemu_plugin_tb *tb) {
    (void)id;
    qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &insns,
                                             qemu_plugin_tb_n_insns(tb));
}

static void syscall(qemu_plugin_id_t id, unsigned int vcpu, int64_t num, uint64_t a1,
                    uint64_t a2, uint64_t a3, uint64_t a4, uint64_t a5, uint64_t a6,
                    uint64_t a7, uint64_t a8) {
    (void)id, (void)vcpu, (void)a1, (void)a2, (void)a3, (void)a4, (void)a5, (void)a6;
    (void)a7, (void)a8;
    if (num == SYS_CLOCK_GETTIME) {
        fprintf(out, "%" PRIu64 "\n", insns);
    }
}

static void finished(qemu_plugin_id_t id, void *data) {
    (void)id, (void)data;
    fflush(out);
    fprintf(stderr, "insns: %" PRIu64 "\n", insns);
}

__attribute__((visibility("default"))) int qemu_plugin_install(qemu_plugin_id_t id,
                                                               const qemu_info_t *info,
                                                               int argc, char **argv) {
    (void)info;
    out = stderr;
    for (int i = 0; i < argc; i++) {
        if (strncmp(argv[i], "out=", 4) == 0 && !(out = fopen(argv[i] + 4, "w"))) {
            return -1;
        }
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, translated);
    qemu_plugin_register_vcpu_syscall_cb(id, syscall);
    qemu_plugin_register_atexit_cb(id, finished, NULL);
    return 0;
}
