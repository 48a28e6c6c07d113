% Listings A2-A4 of Pineda et al. (2021), "Deliberative and Conceptual Inference in
% Service Robots" (CC BY 4.0), in SitLog's own notation, as printed except for one
% repair: Listing A3 embeds 'sample_wait', but the DM of Listing A4 is called wait.
% The user functions f, g, h of Listing A5 are Python here.
functions(['homebot.sitlog.functions.appendix_a']).

Global_Vars = [g_count_fs1 ==> 0,
g_count_fs2 ==> 0].


% Main Dialogue Model
diag_mod(main,
%Second argument: List of Situations
[% Initial situation
[id ==> is,
type ==> speech,
in_arg ==> In_Arg,
out_arg ==> apply(when(If,True,False),
[In_Arg=='monday','tuesday','monday']),
% Local program
prog ==> [inc(count_init,Count_Init)],
arcs ==>
[% Examples of Grounded forms
finish:screen('Good Bye') => fs,
% Example of predicate expectation and action
[day(X)]:[date(get(day,Y)), next_date(set(day,X))] => is,
% Example of functional specification of
% expectation, action and next situation
[get(day,Day),apply(f(X),[In_Arg])]: [apply(g(X),[_])] =>
apply(h(X,Y),[In_Arg,Day])
]
],
% Second Situation
[id ==> rs,
type ==> recursive,
prog ==> [inc(count_rec, Count_Rec)],
embedded_dm ==> wait,
arcs ==> [fs1:screen('Back to initial sit') => is,
fs2:screen('Cont. recursive sit') => rs]
],
% Final Situation
[id ==> fs, type ==> final]
], % End list of situations
% Third Argument: List of Local Variables
[day ==> monday, count_init ==> 0, count_rec ==> 0]
). %End DM (main)



% Second Dialogue Model
diag_mod(wait,
% Second argument: List of Situations
[% First situation
[id ==> is,
type ==> speech,
in_arg ==> In_Arg,
arcs ==>
[
In_Arg:[inc(g_count_fs1, G1)] => fs1,
loop:[inc(g_count_fs2, G2)] => fs2
]
],
% Final Situation 1
[id ==> fs1, type ==> final],
% Final Situation 2
[id ==> fs2, type ==> final]
], % End List of Situations
% Third argument: local variables (empty)
[ ]
). % End DM (wait)

