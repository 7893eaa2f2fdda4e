"""The lab's engine and shell: scene contract, fixed-step loop, window, headless runner, benchmarks.

Nothing in `app/` is scene content; scenes live in `scenes/` and are listed in `scenes/__init__.py`.
"""
