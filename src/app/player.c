/* player.c: the intro player, the desktop twin of the original 64 kB intro: plays the built-in intro in a window (build/intro-fixed, build/intro-float), with play's options (cli.c) but --scene. */
#include "cli.h"
#include "scn.h"

int app_main(int argc, char **argv)
{
    cli_opts o = cli_defaults(CLI_INTRO);
    int rc = argc > 0 ? cli_parse(CLI_INTRO, argc - 1, argv + 1, &o) : 0;
    if (rc != 0)
        return rc < 0 ? 0 : rc; /* -1: --help, --version */
    play_opts p = cli_play_opts(&o);
    p.desc = &scn_intro;
    p.name = "intro";
    return play_run(&p);
}
