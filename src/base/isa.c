/* The SIMD path of the hot kernels (lucent/base.h, "SIMD paths"): what the CPU supports, what the
 * process asked for (lucent_isa_set, else LUCENT_ISA), and the path in use. The per-ISA objects are
 * compiled with their own -m flags (CMakeLists.txt: LUCENT_SIMD_X86) and only ever called after
 * lucent_isa_active() has said the CPU runs them. */
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/base.h"

static const char *const k_names[LUCENT_ISA_COUNT] = {"auto", "scalar", "avx2", "avx512"};

static _Atomic int g_isa = LUCENT_ISA_AUTO; /* what lucent_isa_set asked for */
static lucent_isa g_env = LUCENT_ISA_AUTO;  /* LUCENT_ISA, resolved once */
static pthread_once_t g_env_once = PTHREAD_ONCE_INIT;

const char *lucent_isa_name(lucent_isa isa) { return (int)isa >= 0 && isa < LUCENT_ISA_COUNT ? k_names[isa] : NULL; }

lucent_status lucent_isa_parse(const char *name, lucent_isa *dest)
{
    for (int i = 0; name && i < LUCENT_ISA_COUNT; i++)
        if (!strcmp(name, k_names[i])) {
            *dest = (lucent_isa)i;
            return LUCENT_OK;
        }
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown instruction set \"%s\" (auto, scalar, avx2, avx512)",
                        name ? name : "");
}

bool lucent_isa_supported(lucent_isa isa)
{
    switch (isa) {
    case LUCENT_ISA_AUTO:
    case LUCENT_ISA_SCALAR: return true;
#if defined(LUCENT_SIMD_X86)
    /* __builtin_cpu_supports checks the CPU's flags and that the OS saves the vector state (XCR0) */
    case LUCENT_ISA_AVX2: return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    case LUCENT_ISA_AVX512:
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("avx512f") &&
               __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
               __builtin_cpu_supports("avx512vl");
#endif
    default: return false;
    }
}

static lucent_isa best(void)
{
    for (int i = LUCENT_ISA_COUNT - 1; i > LUCENT_ISA_SCALAR; i--)
        if (lucent_isa_supported((lucent_isa)i)) return (lucent_isa)i;
    return LUCENT_ISA_SCALAR;
}

static void read_env(void)
{
    const char *e = getenv("LUCENT_ISA");
    lucent_isa isa = LUCENT_ISA_AUTO;
    if (!e || !*e) {
        g_env = best();
    } else if (lucent_isa_parse(e, &isa) != LUCENT_OK || !lucent_isa_supported(isa)) {
        g_env = best();
        lucent_log(LUCENT_LOG_WARN, "LUCENT_ISA=%s: %s; using %s", e,
                   lucent_isa_name(isa) && isa != LUCENT_ISA_AUTO ? "this CPU lacks it"
                                                                  : "unknown (auto, scalar, "
                                                                    "avx2, avx512)",
                   lucent_isa_name(g_env));
    } else {
        g_env = isa == LUCENT_ISA_AUTO ? best() : isa;
    }
}

lucent_status lucent_isa_set(lucent_isa isa)
{
    if ((int)isa < 0 || isa >= LUCENT_ISA_COUNT)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "instruction set %d: no such path", (int)isa);
    if (!lucent_isa_supported(isa))
        return lucent_error(LUCENT_ERR_UNSUPPORTED, "instruction set %s: this CPU (or this build) lacks it",
                            lucent_isa_name(isa));
    atomic_store(&g_isa, (int)isa);
    return LUCENT_OK;
}

lucent_isa lucent_isa_active(void)
{
    lucent_isa isa = (lucent_isa)atomic_load(&g_isa);
    if (isa != LUCENT_ISA_AUTO) return isa;
    pthread_once(&g_env_once, read_env);
    return g_env;
}
