; (options): the compile-time settings of Debian's CLIPS 6.30 build.
(options)
(options 1)
(get-function-restrictions options)
(exit)
