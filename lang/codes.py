"""Diagnostic codes of the language front end (E0xx): lexical and syntax errors."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = [
    "SYNTAX", "UNEXPECTED_CHARACTER", "UNTERMINATED_STRING", "UNBALANCED_BRACE",
    "UNEXPECTED_END", "MISSPELT_KEYWORD", "UNKNOWN_UNIT", "RESERVED_KEYWORD", "EMPTY_FILE",
    "BINARY_INPUT", "LONE_CR", "UNICODE_LINE_BREAK", "NOT_FINITE_LITERAL",
]

SYNTAX = Code("E001", "syntax", "the text does not follow the grammar at this token")
UNEXPECTED_CHARACTER = Code("E002", "unexpected-character", "a character that starts no token")
UNTERMINATED_STRING = Code("E003", "unterminated-string", 'a string has no closing \'"\' on its line')
UNBALANCED_BRACE = Code("E004", "unbalanced-brace", "a '{' is never closed or a '}' closes nothing")
UNEXPECTED_END = Code("E005", "unexpected-end", "the file ends in the middle of a statement")
MISSPELT_KEYWORD = Code("E006", "misspelt-keyword", "a name stands where a keyword is expected")
UNKNOWN_UNIT = Code("E007", "unknown-unit", "a number is followed by a word that is not a unit")
RESERVED_KEYWORD = Code("E008", "reserved-keyword", "a keyword is used as a name")
EMPTY_FILE = Code("E009", "empty-file", "the file holds no statement")
BINARY_INPUT = Code("E010", "binary-input", "the file holds control characters: not a text file")

# line breaks other tools count and the lexer does not; numbers too big for a float
LONE_CR = Code("E011", "lone-carriage-return", "a carriage return not followed by a line feed (old Mac line ending)")
UNICODE_LINE_BREAK = Code("E012", "unicode-line-break", "U+0085, U+2028 or U+2029: a line break only some tools count")
NOT_FINITE_LITERAL = Code("E013", "number-too-large", "a number literal too large for a 64-bit float (it would be infinite)")
