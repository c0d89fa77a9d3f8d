// SPDX-License-Identifier: GPL-2.0-or-later
// exports['.']: importing defines <tangent-field-designer> (when the name is free).
export * from './element.js';
import { TangentFieldDesigner } from './element.js';
export default TangentFieldDesigner;
