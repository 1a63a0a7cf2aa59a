"""The rooms of the class server, one module per resource (they import the store layer,
never each other in a circle): play, board, lecturer, debrief, exports, department, with
common (what every room asks of a request) and answers (headers, refusals)."""
