// The edits, one command per file. A command is data and bookkeeping, and makes no request itself: the session
// (session.js #perform) sends the one request a step needs, takes the reply's snapshot on, and then lets the
// command map its page ids; history.js only stacks the commands. Each has
//   request(table) / undoRequest(table): {op, args}, the worker request of the step or of taking it back (null:
//     nothing to do);
//   applied(reply, table) / undone(reply, table) (optional): after the reply's design is the table's; may return
//     a notice the user is shown;
//   refused(table, forward) (optional): after a request the core refused, whose reply put the design back;
//   label, result, changes (false: not recorded), clearsSelection, serialize() and a static deserialize().
import { AddConstraint } from './add-constraint.js';
import { AddSingularity } from './add-singularity.js';
import { AddSingularities } from './add-singularities.js';
import { AddSingularityPair } from './add-singularity-pair.js';
import { MoveSingularity } from './move-singularity.js';
import { RemoveConstraint } from './remove-constraint.js';
import { ReplaceDesign } from './replace-design.js';
import { SetParameter } from './set-parameter.js';
import { SetFeatures } from './set-features.js';
import { SetSetting } from './set-setting.js';
import { SetSymmetry } from './set-symmetry.js';

export {
  AddConstraint,
  AddSingularity,
  AddSingularities,
  AddSingularityPair,
  MoveSingularity,
  RemoveConstraint,
  ReplaceDesign,
  SetFeatures,
  SetParameter,
  SetSetting,
  SetSymmetry,
};

const COMMANDS = [
  AddConstraint,
  AddSingularity,
  AddSingularities,
  AddSingularityPair,
  MoveSingularity,
  RemoveConstraint,
  ReplaceDesign,
  SetFeatures,
  SetParameter,
  SetSetting,
  SetSymmetry,
];

// A command from its serialize() form.
export function deserializeCommand(json) {
  const Command = COMMANDS.find((C) => C.type === json?.type);
  if (!Command) throw new Error(`unknown command ${JSON.stringify(json?.type)}`);
  return Command.deserialize(json);
}
