"""Drawing helpers: the world<->screen view, text, pymunk and cloth drawing, charts. Uses pygame."""
