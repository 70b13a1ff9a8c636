/* arm_fault.c: a test program for the board backends: executes an undefined instruction, which must end the run through the exception vectors with status 3 (tests/arm.sh, tests/m3.sh). */
#include "platform.h"

int app_main(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    plat_log("arm_fault: executing an undefined instruction");
#if defined(__thumb__)
    __asm__ volatile("udf #0"); /* Cortex-M3: a UsageFault, taken as a HardFault */
#else
    __asm__ volatile(".word 0xe7f000f0");
#endif
    plat_log("arm_fault: still running after it");
    return 0;
}
