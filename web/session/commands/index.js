// The edits, one command per file (execute / undo / serialize); history.js only stacks them.
import { AddConstraint } from './add-constraint.js';
import { RemoveConstraint } from './remove-constraint.js';
import { ReplaceDesign } from './replace-design.js';
import { SetParameter } from './set-parameter.js';
import { SetSetting } from './set-setting.js';
import { SetSymmetry } from './set-symmetry.js';

export { AddConstraint, RemoveConstraint, ReplaceDesign, SetParameter, SetSetting, SetSymmetry };

const COMMANDS = [AddConstraint, RemoveConstraint, ReplaceDesign, SetParameter, SetSetting, SetSymmetry];

// A command from its serialize() form.
export function deserializeCommand(json) {
  const Command = COMMANDS.find((C) => C.type === json?.type);
  if (!Command) throw new Error(`unknown command ${JSON.stringify(json?.type)}`);
  return Command.deserialize(json);
}
