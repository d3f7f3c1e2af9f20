/* The arrow keys for the Graphics window.

   Graphics turns each key press into the characters that XLookupString
   gives it, and the arrow keys give none, so it never reports them. Xlib
   can bind a string to a keysym for one connection (XRebindKeysym); this
   binds one character to each arrow key on the connection that Graphics
   opened, so that the arrows arrive through read_key like other keys. */

#include <X11/Xlib.h>
#include <X11/keysym.h>
#include <X11/XKBlib.h>
#include <caml/mlvalues.h>
#include <caml/alloc.h>
#include <caml/memory.h>

/* Graphics' connection to the X server (graphics/src/unix/open.c);
   NULL while no window is open. */
extern Display *caml_gr_display;

/* [chars] holds the characters for Left, Up, Right and Down. They are
   bound with no modifier and with Num Lock or Caps Lock on, for the main
   arrows and the keypad's. Returns false if no window is open. */
value raytrace_bind_arrows(value chars)
{
  static const KeySym keys[8] = { XK_Left, XK_Up, XK_Right, XK_Down,
                                  XK_KP_Left, XK_KP_Up, XK_KP_Right, XK_KP_Down };
  static KeySym num_lock[1] = { XK_Num_Lock };
  static KeySym caps_lock[1] = { XK_Caps_Lock };
  static KeySym both[2] = { XK_Num_Lock, XK_Caps_Lock };
  const unsigned char *s = (const unsigned char *) String_val(chars);
  int i;
  if (caml_gr_display == NULL || caml_string_length(chars) != 4) return Val_false;
  /* XRebindKeysym looks the modifiers up while it holds the display's
     lock, and a first look-up fetches the keyboard map, which takes the
     lock again: a deadlock in libX11. Looking them up once before avoids
     it (the map is then cached). */
  XkbKeysymToModifiers(caml_gr_display, XK_Num_Lock);
  XkbKeysymToModifiers(caml_gr_display, XK_Caps_Lock);
  for (i = 0; i < 8; i++) {
    const unsigned char *c = s + (i % 4);
    XRebindKeysym(caml_gr_display, keys[i], NULL, 0, c, 1);
    XRebindKeysym(caml_gr_display, keys[i], num_lock, 1, c, 1);
    XRebindKeysym(caml_gr_display, keys[i], caps_lock, 1, c, 1);
    XRebindKeysym(caml_gr_display, keys[i], both, 2, c, 1);
  }
  return Val_true;
}

/* The size in pixels of the default screen of the display that Graphics
   will open ($DISPLAY), as the pair (width, height); (0, 0) if no display
   can be opened (Graphics then says why). Its connection is its own, and
   stays open until the process ends: an X server started for one program
   (xvfb-run) resets when its last client leaves, and would refuse
   Graphics' connection while it does. */
value raytrace_screen_size(value unit)
{
  static Display *d = NULL;
  int w = 0, h = 0;
  value pair;
  (void) unit;
  if (d == NULL) d = XOpenDisplay(NULL);
  if (d != NULL) {
    w = DisplayWidth(d, DefaultScreen(d));
    h = DisplayHeight(d, DefaultScreen(d));
  }
  pair = caml_alloc_tuple(2);
  Store_field(pair, 0, Val_int(w));
  Store_field(pair, 1, Val_int(h));
  return pair;
}
