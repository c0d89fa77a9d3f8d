// Package entry exports['./element']: the class and define(tagName?), with no side effects.
export { TAG_NAME, TangentFieldDesigner, define } from './element/element.js';
