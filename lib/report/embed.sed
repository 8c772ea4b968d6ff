# A text file as the lines of a C string literal: backslashes and quotes
# escaped, each line ending in \n.
s/\\/\\\\/g
s/"/\\"/g
s/^/"/
s/$/\\n"/
