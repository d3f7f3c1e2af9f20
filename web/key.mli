(** Browser keys as the window's keys.

    The page receives the [key] property of keyboard events
    ({{:https://developer.mozilla.org/en-US/docs/Web/API/KeyboardEvent/key}MDN}):
    ["a"], ["D"] with Shift held, ["ArrowLeft"], ["Escape"] ... {!Raytrace_view.View}
    takes the characters that the Graphics window receives. *)

val to_char : string -> char option
(** [to_char key] is the character {!Raytrace_view.View.handle} takes for the
    browser key named [key]: the key itself for a one-character ASCII
    name, {!Raytrace_view.View.arrow_left} ... {!Raytrace_view.View.arrow_down} for
    ["ArrowLeft"] ... ["ArrowDown"], ['\027'] for ["Escape"], and [None]
    for every other key (Shift, F1, "é" ...). *)
