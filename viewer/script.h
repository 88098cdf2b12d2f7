/* `lucent view --script`: the actions of a script, checked whole before any runs (issue 32 item 15:
 * a typo on line 4 was reported after the three lines before it had run). script_parse.c checks a
 * script's text without a window or a renderer (only the lucent headers), so that the fuzz target
 * (fuzz/fuzz_view_script.c) can call it; script.c plays the checked actions. docs/view.md lists
 * them. */
#ifndef LUCENT_VIEWER_SCRIPT_H
#define LUCENT_VIEWER_SCRIPT_H

#include <stdbool.h>
#include <stddef.h>

#include "lucent/lucent.h"

enum { VIEWER_SCRIPT_WORDS = 16, VIEWER_SCRIPT_LINE = 4094, VIEWER_SCRIPT_EDITS = 4 };

typedef enum viewer_action {
    VIEWER_ORBIT = 0,
    VIEWER_PAN,
    VIEWER_ZOOM,
    VIEWER_RESET,
    VIEWER_LIGHT,
    VIEWER_SET,
    VIEWER_METHOD,
    VIEWER_METHOD_B,
    VIEWER_LAYOUT,
    VIEWER_OBJECT,
    VIEWER_MATERIAL,
    VIEWER_LOAD_REFERENCE,
    VIEWER_SHOW,
    VIEWER_SAVE_SCENE,
    VIEWER_SCREENSHOT,
    VIEWER_WINDOW_SHOT,
    VIEWER_EXPORT_TAPS,
    VIEWER_RESIZE,
    VIEWER_PRINT,
    VIEWER_BENCH,
    VIEWER_FRAMES,
    VIEWER_WAIT_RELOAD,
    VIEWER_TRACE_START,
    VIEWER_TRACE_WAIT,
    VIEWER_TRACE_STOP,
    VIEWER_KEY,
    VIEWER_UI_FRAMES,
    VIEWER_PANEL,
    VIEWER_QUIT,
    VIEWER_ACTION_COUNT
} viewer_action;

/* The keys `key` taps (the window's keys, docs/view.md). */
typedef enum viewer_key { VIEWER_KEY_R = 0, VIEWER_KEY_TAB, VIEWER_KEY_ESCAPE, VIEWER_KEY_1 } viewer_key;

/* A material edit: sigma_a, sigma_s_prime, g (per channel) or eta. */
typedef enum viewer_edit {
    VIEWER_EDIT_SIGMA_A = 0,
    VIEWER_EDIT_SIGMA_S_PRIME,
    VIEWER_EDIT_G,
    VIEWER_EDIT_ETA,
    VIEWER_EDIT_MELANIN, /* a spectral skin's chromophores (docs/skin.md): one number in [0, 1] */
    VIEWER_EDIT_EUMELANIN,
    VIEWER_EDIT_BLOOD,
    VIEWER_EDIT_OXYGENATION
} viewer_edit;

/* One checked line. */
typedef struct viewer_command {
    int line;
    viewer_action action;
    bool async;                     /* do not wait for the bakes (and frames) it starts */
    int argc;                       /* words after the action */
    char *arg[VIEWER_SCRIPT_WORDS]; /* in the script's text */
    double x[4];                    /* the numbers among them */
    int choice;                     /* layout, show, key (+ digit - 1), panel all, export format */
    int edit_count;                 /* material edits, in order */
    viewer_edit edit[VIEWER_SCRIPT_EDITS];
    double edit_value[VIEWER_SCRIPT_EDITS][3];
} viewer_command;

typedef struct viewer_script {
    char *text; /* the script, its lines cut at the words */
    viewer_command *commands;
    int count;
} viewer_script;

/* What the check may look at; zero means "unknown" (counts) or "no" (the flags). */
typedef struct viewer_script_context {
    int light_count, object_count; /* light and object indices are checked against these when > 0 */
    bool window;                   /* there is a window (window-shot) */
    bool resolve_materials;        /* `material NAME` reads the preset or file now */
} viewer_script_context;

/* Checks a whole script (size bytes of text, NUL bytes included): every action, its words and its
 * numbers. On failure: LUCENT_ERR_PARSE (or what a setting's reader returns), the message naming
 * name, the line and the action; dest is then empty. Free with viewer_script_free. */
lucent_status viewer_script_parse(const char *text, size_t size, const char *name, const viewer_script_context *ctx,
                                  viewer_script *dest);
void viewer_script_free(viewer_script *s);

/* The action's name as scripts spell it ("orbit"). */
const char *viewer_action_name(viewer_action a);

#endif
