/* arm_fault.c: a test program for the ARM backend: executes an undefined instruction, which must end the run through the exception vectors with status 3 (tests/arm.sh). */
#include "platform.h"

int app_main(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    plat_log("arm_fault: executing an undefined instruction");
    __asm__ volatile(".word 0xe7f000f0");
    plat_log("arm_fault: still running after it");
    return 0;
}
