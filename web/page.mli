(** The web page's program: it wires [index.html]'s canvas, editor,
    selectors and download link to {!Raytrace_web.Session}, paints the
    bands that the session traces in slices between the browser's events,
    and gives the tests a small API on [window.raytrace]. It exports
    nothing to OCaml: everything it does is through the page. *)
